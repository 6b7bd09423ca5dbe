//! `DofMap`: which displacement dofs are free unknowns, imposed (eliminated, with
//! reactions recovered) or linked to others by linear relations (eliminated too).
//!
//! Dof d of node n is 2n + component. The full displacement is u = T x + G g, where x are
//! the free unknowns and g the imposed values at the current time (one per dof, then one
//! per relation right-hand side); relations Σ a_i u_i = b are solved for one of their dofs
//! (the one with the largest coefficient after substitution), so the reduced system stays
//! symmetric: Tᵀ K T.

use crate::error::{Error, Result};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Role {
    Free(usize),
    Fixed,
    Linked(usize),
}

/// u_d = Σ c_k x_k + Σ s_j g_j: free unknowns x and imposed values g (see `expand`).
#[derive(Clone, Debug, Default)]
pub struct LinkExpr {
    pub terms: Vec<(usize, f64)>,
    pub sources: Vec<(usize, f64)>,
}

/// Adds c · `from` to `into`, merging equal indices.
fn add_scaled(into: &mut Vec<(usize, f64)>, from: &[(usize, f64)], c: f64) {
    for &(k, ck) in from {
        match into.iter_mut().find(|t| t.0 == k) {
            Some(t) => t.1 += c * ck,
            None => into.push((k, c * ck)),
        }
    }
}

/// A linear relation between dofs: Σ coef · u_dof = rhs. `name` appears in errors.
#[derive(Clone, Debug)]
pub struct Relation {
    pub terms: Vec<(usize, f64)>,
    pub rhs: f64,
    pub name: String,
}

#[derive(Clone, Debug)]
pub struct DofMap {
    pub roles: Vec<Role>,
    /// Imposed value of each Fixed dof at load factor 1 (0 elsewhere).
    pub prescribed: Vec<f64>,
    /// Right-hand side of each relation at load factor 1.
    pub rhs: Vec<f64>,
    pub exprs: Vec<LinkExpr>,
    pub num_free: usize,
}

impl DofMap {
    /// `used[d]` is false for dofs of nodes that belong to no 2D cell: they are fixed at 0.
    pub fn new(used: &[bool], fixed: &[(usize, f64)], relations: &[Relation]) -> Result<DofMap> {
        let n = used.len();
        let mut fixed_val: Vec<Option<f64>> = vec![None; n];
        for (d, is_used) in used.iter().enumerate() {
            if !is_used {
                fixed_val[d] = Some(0.0);
            }
        }
        for &(d, v) in fixed {
            fixed_val[d] = Some(v);
        }
        // Expressions over raw dof ids that are still free.
        let mut link: Vec<Option<LinkExpr>> = vec![None; n];
        // value of source j (imposed dof, then relation rhs) at load factor 1
        let source_value = |j: usize, fixed_val: &[Option<f64>]| -> f64 {
            if j < n {
                fixed_val[j].unwrap_or(0.0)
            } else {
                relations[j - n].rhs
            }
        };
        for (r, rel) in relations.iter().enumerate() {
            let mut terms: Vec<(usize, f64)> = vec![];
            let mut sources: Vec<(usize, f64)> = vec![(n + r, 1.0)];
            for &(d, a) in &rel.terms {
                if fixed_val[d].is_some() {
                    add_scaled(&mut sources, &[(d, 1.0)], -a);
                } else if let Some(e) = &link[d] {
                    add_scaled(&mut sources, &e.sources, -a);
                    for &(k, c) in &e.terms {
                        terms.push((k, a * c));
                    }
                } else {
                    terms.push((d, a));
                }
            }
            terms.sort_by_key(|t| t.0);
            let mut merged: Vec<(usize, f64)> = vec![];
            for (k, c) in terms {
                match merged.last_mut() {
                    Some(last) if last.0 == k => last.1 += c,
                    _ => merged.push((k, c)),
                }
            }
            let scale = rel.terms.iter().map(|t| t.1.abs()).fold(0.0, f64::max);
            merged.retain(|t| t.1.abs() > 1e-12 * scale);
            let Some(&(pivot, a_p)) = merged.iter().max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
            else {
                let rhs: f64 = sources
                    .iter()
                    .map(|&(j, c)| c * source_value(j, &fixed_val))
                    .sum();
                if rhs.abs() > 1e-12 * (1.0 + rel.rhs.abs()) {
                    return Err(Error::model(format!(
                        "relation '{}' contradicts the imposed displacements or earlier relations",
                        rel.name
                    )));
                }
                continue; // redundant relation
            };
            let expr = LinkExpr {
                terms: merged
                    .iter()
                    .filter(|t| t.0 != pivot)
                    .map(|&(k, c)| (k, -c / a_p))
                    .collect(),
                sources: sources.iter().map(|&(j, c)| (j, c / a_p)).collect(),
            };
            // Substitute the new link into the existing ones that use the pivot.
            for e in link.iter_mut().flatten() {
                if let Some(pos) = e.terms.iter().position(|t| t.0 == pivot) {
                    let c = e.terms.remove(pos).1;
                    add_scaled(&mut e.sources, &expr.sources, c);
                    add_scaled(&mut e.terms, &expr.terms, c);
                }
            }
            link[pivot] = Some(expr);
        }
        let mut roles = vec![Role::Fixed; n];
        let mut free_index = vec![usize::MAX; n];
        let mut num_free = 0;
        for d in 0..n {
            if fixed_val[d].is_none() && link[d].is_none() {
                roles[d] = Role::Free(num_free);
                free_index[d] = num_free;
                num_free += 1;
            }
        }
        let mut exprs = vec![];
        for d in 0..n {
            if let Some(e) = link[d].take() {
                roles[d] = Role::Linked(exprs.len());
                exprs.push(LinkExpr {
                    terms: e.terms.iter().map(|&(k, c)| (free_index[k], c)).collect(),
                    sources: e.sources,
                });
            }
        }
        let prescribed = fixed_val.iter().map(|v| v.unwrap_or(0.0)).collect();
        Ok(DofMap {
            roles,
            prescribed,
            rhs: relations.iter().map(|r| r.rhs).collect(),
            exprs,
            num_free,
        })
    }

    pub fn num_dofs(&self) -> usize {
        self.roles.len()
    }

    /// Full displacement vector from the free unknowns `x` and the imposed values `g`: one
    /// per dof (read at the Fixed dofs), then one per relation right-hand side.
    pub fn expand(&self, x: &[f64], g: &[f64], u: &mut [f64]) {
        for (d, role) in self.roles.iter().enumerate() {
            u[d] = match *role {
                Role::Free(j) => x[j],
                Role::Fixed => g[d],
                Role::Linked(e) => {
                    let e = &self.exprs[e];
                    e.sources.iter().map(|&(j, c)| c * g[j]).sum::<f64>()
                        + e.terms.iter().map(|&(k, c)| c * x[k]).sum::<f64>()
                }
            };
        }
    }

    /// Free unknowns read back from a full vector.
    pub fn restrict(&self, u: &[f64], x: &mut [f64]) {
        for (d, role) in self.roles.iter().enumerate() {
            if let Role::Free(j) = *role {
                x[j] = u[d];
            }
        }
    }

    /// Reduced vector Tᵀ r of a full vector r.
    pub fn reduce(&self, r: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for (d, role) in self.roles.iter().enumerate() {
            match *role {
                Role::Free(j) => out[j] += r[d],
                Role::Fixed => {}
                Role::Linked(e) => {
                    for &(k, c) in &self.exprs[e].terms {
                        out[k] += c * r[d];
                    }
                }
            }
        }
    }

    /// Makes dof `d` follow Σ c · u_k over other dofs (`combo`), plus its own imposed value
    /// g_d when `own_source` (a rigid surface's node: its reference point's dofs, the
    /// imposed part of its rotation). Each u_k enters as it is: free, imposed or linked.
    pub fn set_link(&mut self, d: usize, combo: &[(usize, f64)], own_source: bool) {
        let mut e = LinkExpr::default();
        for &(k, c) in combo {
            match self.roles[k] {
                Role::Free(j) => add_scaled(&mut e.terms, &[(j, 1.0)], c),
                Role::Fixed => add_scaled(&mut e.sources, &[(k, 1.0)], c),
                Role::Linked(i) => {
                    let x = self.exprs[i].clone();
                    add_scaled(&mut e.terms, &x.terms, c);
                    add_scaled(&mut e.sources, &x.sources, c);
                }
            }
        }
        if own_source {
            add_scaled(&mut e.sources, &[(d, 1.0)], 1.0);
        }
        match self.roles[d] {
            Role::Linked(i) => self.exprs[i] = e,
            _ => {
                self.roles[d] = Role::Linked(self.exprs.len());
                self.exprs.push(e);
            }
        }
    }

    /// The free unknowns (with coefficients) that full dof `d` depends on.
    pub fn expand_dof(&self, d: usize, out: &mut Vec<(usize, f64)>) {
        out.clear();
        match self.roles[d] {
            Role::Free(j) => out.push((j, 1.0)),
            Role::Fixed => {}
            Role::Linked(e) => out.extend_from_slice(&self.exprs[e].terms),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relations_are_eliminated_consistently() {
        // 4 dofs: d0 fixed at 2, relation u1 - u2 = 0, relation u2 + u0 - u3 = 1.
        let used = [true; 4];
        let rels = vec![
            Relation {
                terms: vec![(1, 1.0), (2, -1.0)],
                rhs: 0.0,
                name: "r1".into(),
            },
            Relation {
                terms: vec![(2, 1.0), (0, 1.0), (3, -1.0)],
                rhs: 1.0,
                name: "r2".into(),
            },
        ];
        let m = DofMap::new(&used, &[(0, 2.0)], &rels).unwrap();
        assert_eq!(m.num_free, 1);
        let x = vec![0.7];
        let mut u = vec![0.0; 4];
        let g: Vec<f64> = m.prescribed.iter().chain(&m.rhs).copied().collect();
        m.expand(&x, &g, &mut u);
        assert!((u[0] - 2.0).abs() < 1e-15);
        assert!((u[1] - u[2]).abs() < 1e-15);
        assert!((u[2] + u[0] - u[3] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn contradictory_relation_is_an_error() {
        let rels = vec![Relation {
            terms: vec![(0, 1.0)],
            rhs: 1.0,
            name: "tie".into(),
        }];
        let err = DofMap::new(&[true], &[(0, 0.0)], &rels).unwrap_err();
        assert_eq!(
            err.to_string(),
            "relation 'tie' contradicts the imposed displacements or earlier relations"
        );
    }
}
