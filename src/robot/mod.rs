//! Robot description and kinematics. PLACEHOLDER: the robot-model work
//! (issue 3) replaces this file; keep `Robot`, `Robot::basr()` and
//! `Robot::sha256()` with these signatures.

use serde::{Deserialize, Serialize};

/// The immutable description of one robot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Robot {
    pub name: String,
}

impl Robot {
    /// The embedded default robot (BASR).
    pub fn basr() -> Robot {
        Robot {
            name: "BASR".into(),
        }
    }

    /// SHA-256 of the description's canonical form (see `crate::job::canonical_json`).
    pub fn sha256(&self) -> String {
        let v = serde_json::to_value(self).expect("robot serialises");
        crate::io::sha256_hex(&crate::job::canonical_json(&v))
    }
}
