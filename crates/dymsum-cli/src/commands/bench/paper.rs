//! The paper's 13 models (Fig. 3) in its order, and its Table 1 as data.
//!
//! The speedups come from `data/table1_paper.csv` (see `data/SOURCE.md`):
//! the paper's t_bf / t_d for every unordered pair, copied verbatim.
//!
//! ```
//! use dymsum_cli::commands::bench::paper::{paper_speedup, MODELS};
//! assert_eq!(MODELS.len(), 13);
//! assert_eq!(paper_speedup("ellipse", "ellipse"), Some(176.34));
//! // Unordered: either order finds the figure.
//! assert_eq!(paper_speedup("cone", "cube"), Some(8.58));
//! assert_eq!(paper_speedup("vrod", "ti"), Some(67.24));
//! ```

use std::collections::HashMap;
use std::sync::OnceLock;

/// The paper's Table 1 (t_bf / t_d), as shipped: `P,Q,speedup` rows.
pub const TABLE1_CSV: &str = include_str!("../../../data/table1_paper.csv");

/// The 13 models in the paper's order: (built-in name, paper name).
pub const MODELS: [(&str, &str); 13] = [
    ("cone", "cone"),
    ("cube", "cube"),
    ("cylinder", "cylinder"),
    ("dd", "DD"),
    ("ellipse", "ellipse"),
    ("gs1", "GS1"),
    ("gs2", "GS2"),
    ("gs3", "GS3"),
    ("gs4", "GS4"),
    ("hp", "HP"),
    ("t", "T"),
    ("ti", "TI"),
    ("vrod", "v-rod"),
];

/// The paper's name of a built-in model (`dd` → `DD`); the name itself if
/// it is not one of the 13.
pub fn paper_name(model: &str) -> &str {
    MODELS
        .iter()
        .find(|(m, _)| *m == model)
        .map(|(_, p)| *p)
        .unwrap_or(model)
}

/// The built-in name of a paper name (`v-rod` → `vrod`).
fn builtin_name(paper: &str) -> Option<&'static str> {
    MODELS.iter().find(|(_, p)| *p == paper).map(|(m, _)| *m)
}

fn table() -> &'static HashMap<(String, String), f64> {
    static TABLE: OnceLock<HashMap<(String, String), f64>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut map = HashMap::new();
        for line in TABLE1_CSV.lines().skip(1) {
            let cols: Vec<&str> = line.trim().split(',').collect();
            if cols.len() != 3 {
                continue;
            }
            let (Some(p), Some(q), Ok(s)) = (
                builtin_name(cols[0]),
                builtin_name(cols[1]),
                cols[2].parse::<f64>(),
            ) else {
                continue;
            };
            map.insert(key(p, q), s);
        }
        map
    })
}

fn key(a: &str, b: &str) -> (String, String) {
    if a <= b {
        (a.to_string(), b.to_string())
    } else {
        (b.to_string(), a.to_string())
    }
}

/// The paper's speedup of DYMSUM over brute force for the unordered pair
/// of built-in model names, if the paper has it.
pub fn paper_speedup(p: &str, q: &str) -> Option<f64> {
    table().get(&key(p, q)).copied()
}

/// The 91 unordered pairs in the paper's lower-triangular layout: `(row,
/// column)` with the column at or before the row, row by row.
pub fn pairs() -> Vec<(&'static str, &'static str)> {
    let mut out = Vec::with_capacity(91);
    for (i, (row, _)) in MODELS.iter().enumerate() {
        for (col, _) in MODELS.iter().take(i + 1) {
            out.push((*row, *col));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_whole_table_is_read() {
        assert_eq!(table().len(), 91);
        assert_eq!(pairs().len(), 91);
        for (p, q) in pairs() {
            assert!(paper_speedup(p, q).is_some(), "{p} {q}");
        }
        assert_eq!(paper_speedup("gs4", "hp"), Some(11.51));
        assert_eq!(paper_name("vrod"), "v-rod");
    }
}
