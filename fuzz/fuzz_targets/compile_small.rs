//! The whole compile pipeline on short messages with options drawn from the
//! ranges the command line accepts: every combination is compiled or
//! refused, never a panic, an overflow or a hang.
#![no_main]
use basr::plan::compile::{compile_job, CompileRequest, Tilt};
use libfuzzer_sys::fuzz_target;

/// What a message may hold (SPEC §1), space included.
const CHARS: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 ";

fuzz_target!(|data: &[u8]| {
    let Some((opts, text)) = data.split_first_chunk::<7>() else {
        return;
    };
    // Up to 3 characters: compile takes ~0.1 s a letter.
    let message: String = text
        .iter()
        .take(3)
        .map(|b| CHARS[*b as usize % CHARS.len()] as char)
        .collect();
    let unit = |b: u8| f64::from(b) / 255.0;
    let mut req = CompileRequest::message(&message);
    req.overrides.letter_height_m = Some(0.3 + 4.7 * unit(opts[0])); // 1 to 16 ft
    req.overrides.lane_width_m = Some(2.0 + 8.0 * unit(opts[1]));
    req.tilt = match opts[2] % 3 {
        0 => Tilt::None,
        1 => Tilt::Trapezoid,
        _ => Tilt::Quadrilateral,
    };
    req.rung_spacing_m = 1e-3 * (1.0 + 99.0 * unit(opts[3])); // the CLI's 1 mm floor
    req.period_s = 0.005 + 0.2 * unit(opts[4]); // the CLI's 5 ms floor
    req.gun_lead_s = 0.5 * unit(opts[5]);
    req.gun_lag_s = 0.5 * unit(opts[6]);
    let _ = compile_job(&req);
});
