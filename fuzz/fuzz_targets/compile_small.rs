//! The whole compile pipeline on short messages with options drawn from the
//! ranges the command line accepts: every combination is compiled or
//! refused, never a panic, an overflow or a hang.
#![no_main]
use basr::pipeline::compile::{compile_job, CompileRequest, Tilt};
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
    // The command line's ranges (`basr compile --help`): letter height
    // 0.3–10 m (layout::LETTER_HEIGHT_RANGE_M), lane width above 0 and at
    // most 30 m (MAX_LANE_WIDTH_M), rung spacing 1–100 mm, period
    // 0.005–0.1 s, gun lead and lag 0–1 s; both ends of each are drawn.
    req.overrides.letter_height_m = Some(0.3 + 9.7 * unit(opts[0]));
    req.overrides.lane_width_m = Some(30.0 * (f64::from(opts[1]) + 1.0) / 256.0);
    req.tilt = match opts[2] % 3 {
        0 => Tilt::None,
        1 => Tilt::Trapezoid,
        _ => Tilt::Quadrilateral,
    };
    req.rung_spacing_m = 1e-3 * (1.0 + 99.0 * unit(opts[3]));
    req.period_s = 0.005 + 0.095 * unit(opts[4]);
    req.gun_lead_s = unit(opts[5]);
    req.gun_lag_s = unit(opts[6]);
    let _ = compile_job(&req);
});
