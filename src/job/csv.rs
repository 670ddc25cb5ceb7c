//! The setpoint CSV (SPEC §3): a header row of `COLUMNS`, one row per
//! control period.

use std::path::Path;

use super::{Samples, COLUMNS};

/// Write `samples` as CSV atomically to `path`.
pub fn write(samples: &Samples, path: &Path) -> anyhow::Result<()> {
    crate::io::write_atomic_with(path, |w| {
        let mut out = ::csv::Writer::from_writer(w);
        out.write_record(COLUMNS).map_err(std::io::Error::other)?;
        for i in 0..samples.len() {
            out.write_record(samples.csv_fields(i))
                .map_err(std::io::Error::other)?;
        }
        out.flush()
    })?;
    Ok(())
}
