//! What a failure message adds about a load step that did not converge.

use super::Nonlinear;

/// What a failure message adds about an unconverged step: the nodes whose contact status
/// kept changing (with how often), where the residual r is largest, and what may help.
pub(super) fn diagnosis(
    problem: &dyn Nonlinear,
    r: &[f64],
    changes: &std::collections::BTreeMap<usize, usize>,
) -> String {
    let mut out = String::new();
    let mut cycling: Vec<(usize, usize)> = changes
        .iter()
        .filter(|c| *c.1 >= 2)
        .map(|(&n, &k)| (n, k))
        .collect();
    cycling.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    if !cycling.is_empty() {
        let named: Vec<String> = cycling
            .iter()
            .take(6)
            .map(|(n, k)| format!("{} ({k}×)", n + 1))
            .collect();
        let more = cycling.len().saturating_sub(6);
        out += &format!(
            "; contact statuses kept changing at node{} {}{}",
            if cycling.len() > 1 { "s" } else { "" },
            named.join(", "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        );
    }
    if let Some(at) = problem.residual_location(r) {
        out += &format!("; the largest out-of-balance force is at {at}");
    }
    out += if cycling.is_empty() {
        "; more load steps ([solver] steps) or a larger max_iterations may help"
    } else {
        "; more load steps ([solver] steps), or a finer mesh where the statuses change, may help"
    };
    out
}
