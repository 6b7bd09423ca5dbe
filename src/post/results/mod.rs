//! The numbers of a run's outcome as results.json gives them (probes, reactions summed per
//! support group, per contact pair, per output time, the solver's report) and the text of
//! history.csv, kept in memory: the `tribo` command writes them, the Python package hands
//! them back, from this one function so that the two cannot differ.
//!
//! | file | what |
//! |---|---|
//! | `contact.rs` | per contact pair: results.json entries and history.csv columns |
//! | `rigid.rs` | per rigid surface: its reference point's motion and reaction |

pub mod contact;
pub mod rigid;

use crate::case::schema::CaseFile;
use crate::case::Outcome;
use crate::error::Result;
use crate::fem::material::Modelisation;
use crate::mesh::Mesh;
use crate::post::contact_summary::NodeContact;
use crate::post::result_vtu::State;
use contact::{csv_header, csv_values, hertz_fits, pair_json};
use serde_json::{json, Map, Value};
use std::collections::{HashMap, HashSet};

/// What `summary` gives.
pub struct Summary {
    /// results.json's `probes`, `reactions`, `history`, `contact` and `solver`.
    pub json: Value,
    /// history.csv (None when the case asks for no history or nothing was kept).
    pub history_csv: Option<String>,
}

/// The results.json entries and history.csv of `outcome` (the caller adds the run's own:
/// case, title, mesh, status, files, wall time).
pub fn summary(case: &CaseFile, mesh: &Mesh, outcome: &Outcome) -> Result<Summary> {
    let axisymmetric = case.model.modelisation == Modelisation::Axisymmetric;
    let mut contact_json = vec![];
    for (i, (slave, master)) in outcome.contact_surfaces.iter().enumerate() {
        let result = &outcome.contact[i];
        let mut entry = pair_json(&slave.group, &master.group, &result.summary, axisymmetric);
        if case.output.hertz.is_some() {
            let mu = outcome.contact_shear.get(i).map_or(0.0, |s| s.0);
            if let (Value::Object(fits), Some(e)) =
                (hertz_fits(result, mu, &mesh.coords), entry.as_object_mut())
            {
                e.extend(fits);
            }
        }
        contact_json.push(entry);
    }
    let mut probes = Map::new();
    for (name, v) in &outcome.probes {
        probes.insert(name.clone(), json!(v));
    }
    // reactions summed over the groups of the imposed displacements and motions
    let mut support_groups: Vec<&str> =
        case.displacement.iter().map(|d| d.group.as_str()).collect();
    support_groups.extend(case.rotation.iter().map(|r| r.group.as_str()));
    let mut seen = HashSet::new();
    support_groups.retain(|g| seen.insert(*g));
    let mut support_nodes = vec![];
    for g in &support_groups {
        support_nodes.push(mesh.node_group(g)?);
    }
    let group_reactions = |r: &[f64]| -> Vec<[f64; 2]> {
        support_nodes
            .iter()
            .map(|nodes| {
                nodes
                    .iter()
                    .fold([0.0, 0.0], |a, &n| [a[0] + r[2 * n], a[1] + r[2 * n + 1]])
            })
            .collect()
    };
    let reactions_json = |r: &[f64]| -> Map<String, Value> {
        let mut out = Map::new();
        for (g, v) in support_groups.iter().zip(group_reactions(r)) {
            out.insert(g.to_string(), json!({"rx": v[0], "ry": v[1]}));
        }
        out
    };
    let reactions = reactions_json(&outcome.reactions);
    // per output time: probes and reactions (results.json and history.csv)
    let mut history = vec![];
    let mut history_csv = None;
    if case.output.history && !outcome.steps.is_empty() {
        let mut text = String::from("time");
        for p in &case.output.probe {
            text.push_str(&format!(",{}", p.name));
        }
        for g in &support_groups {
            text.push_str(&format!(",rx_{g},ry_{g}"));
        }
        for i in 0..outcome.contact_surfaces.len() {
            text.push_str(&csv_header(i + 1, axisymmetric));
        }
        text.push_str(&rigid::csv_header(&outcome.rigid));
        text.push('\n');
        for st in &outcome.steps {
            let mut probes = Map::new();
            text.push_str(&st.time.to_string());
            for (name, v) in &st.probes {
                probes.insert(name.clone(), json!(v));
                text.push_str(&format!(",{v}"));
            }
            for v in group_reactions(&st.reactions) {
                text.push_str(&format!(",{},{}", v[0], v[1]));
            }
            let mut contact = vec![];
            for (r, (slave, master)) in st.contact.iter().zip(&outcome.contact_surfaces) {
                text.push_str(&csv_values(&r.summary));
                contact.push(pair_json(
                    &slave.group,
                    &master.group,
                    &r.summary,
                    axisymmetric,
                ));
            }
            text.push_str(&rigid::csv_values(&st.rigid));
            text.push('\n');
            history.push(json!({
                "time": st.time,
                "probes": probes,
                "reactions": reactions_json(&st.reactions),
                "contact": contact,
                "rigid": rigid::rigid_json(&st.rigid),
            }));
        }
        history_csv = Some(text);
    }
    Ok(Summary {
        json: json!({
            "probes": probes,
            "reactions": reactions,
            "history": history,
            "contact": contact_json,
            "rigid": rigid::rigid_json(&outcome.rigid),
            "solver": outcome.report,
        }),
        history_csv,
    })
}

/// results.json's description of the run: title, mesh size, modelisation.
pub fn header(case: &CaseFile, mesh: &Mesh) -> Value {
    json!({
        "title": case.title,
        "mesh": {"nodes": mesh.num_nodes(), "cells": mesh.num_cells()},
        "modelisation": case.model.modelisation.name(),
    })
}

/// The final state of `outcome` as the VTU writer takes it.
pub fn final_state(o: &Outcome) -> State<'_> {
    State {
        u: &o.u,
        reactions: &o.reactions,
        stress: &o.stress,
        pk2: o.pk2.as_deref(),
        contact: &o.contact,
        multipliers: &o.contact_multipliers,
    }
}

/// The group of each material, in the case's order, as the VTU writer takes them.
pub fn material_groups(case: &CaseFile) -> Vec<Option<String>> {
    case.material.iter().map(|m| m.group.clone()).collect()
}

/// The contact values of each slave node of `outcome`, the first pair's where a node is on
/// the slave surfaces of several.
pub fn node_contact(outcome: &Outcome) -> HashMap<usize, &NodeContact> {
    let mut at = HashMap::new();
    for r in outcome.contact.iter().rev() {
        for c in &r.nodes {
            at.insert(c.node, c);
        }
    }
    at
}
