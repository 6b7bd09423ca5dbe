//! The `[[rigid]]` outputs of results.json and history.csv: per rigid surface, the motion
//! of its reference point and the reaction there (force and moment the driver exerts).

use crate::case::RigidState;
use serde_json::{json, Value};

/// `{name: {ux, uy, rotation, fx, fy, moment}}`.
pub fn rigid_json(states: &[RigidState]) -> Value {
    let mut out = serde_json::Map::new();
    for s in states {
        out.insert(
            s.name.clone(),
            json!({
                "ux": s.motion[0],
                "uy": s.motion[1],
                "rotation": s.motion[2],
                "fx": s.reaction[0],
                "fy": s.reaction[1],
                "moment": s.reaction[2],
            }),
        );
    }
    Value::Object(out)
}

/// The history.csv columns of each rigid surface.
pub fn csv_header(states: &[RigidState]) -> String {
    states
        .iter()
        .map(|s| {
            let n = &s.name;
            format!(",ux_{n},uy_{n},rotation_{n},fx_{n},fy_{n},moment_{n}")
        })
        .collect()
}

pub fn csv_values(states: &[RigidState]) -> String {
    states
        .iter()
        .flat_map(|s| s.motion.iter().chain(&s.reaction))
        .map(|v| format!(",{v}"))
        .collect()
}
