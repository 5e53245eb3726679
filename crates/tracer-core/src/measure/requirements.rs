//! The requirements table (a TOML file users can edit or replace) and each grid's check
//! against its activity: the maintained average illuminance and the uniformity, each with its
//! margin and whether the margin is larger than its uncertainty (two standard errors).

use super::GridResult;
use serde::Deserialize;

/// The table shipped with raygine (EN 12464-1 rows with their sources).
pub const DEFAULT_REQUIREMENTS: &str =
    include_str!("../../../../assets/requirements/en12464-1.toml");

/// Where the shipped table comes from, for the report.
pub const DEFAULT_SOURCE: &str = "raygine's table (assets/requirements/en12464-1.toml)";

/// One activity's requirements.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Activity {
    pub key: String,
    pub name: String,
    pub em_lx: f64,
    pub u0: f64,
    pub ugr_l: Option<f64>,
    pub ra: Option<f64>,
    pub source: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    activity: Vec<Activity>,
}

/// A parsed requirements table.
#[derive(Clone, Debug)]
pub struct Requirements {
    pub activities: Vec<Activity>,
}

impl Requirements {
    /// Parses a table; errors name `origin` and the line.
    pub fn parse(text: &str, origin: &str) -> Result<Requirements, String> {
        let table: Table = toml::from_str(text).map_err(|e| {
            let line = e
                .span()
                .map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1);
            match line {
                Some(l) => format!("{origin}: line {l}: {}", e.message()),
                None => format!("{origin}: {}", e.message()),
            }
        })?;
        for a in &table.activity {
            if !(a.em_lx >= 0.0 && (0.0..=1.0).contains(&a.u0)) {
                return Err(format!(
                    "{origin}: activity {}: em_lx must be at least 0 and u0 within 0..1",
                    a.key
                ));
            }
        }
        Ok(Requirements {
            activities: table.activity,
        })
    }

    /// The activity `key`, or an error that lists the known keys.
    pub fn activity(&self, key: &str) -> Result<&Activity, String> {
        self.activities
            .iter()
            .find(|a| a.key == key)
            .ok_or_else(|| {
                let known: Vec<&str> = self.activities.iter().map(|a| a.key.as_str()).collect();
                format!(
                    "unknown task \"{key}\": the requirements table has {}",
                    known.join(", ")
                )
            })
    }
}

/// One requirement checked: the value, what is required, the margin (value − required for a
/// minimum, required − value for a maximum: positive passes) and the margin's standard error.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    pub what: String,
    pub value: f64,
    pub required: f64,
    pub std_error: f64,
    /// The requirement is a maximum (UGR), not a minimum.
    pub at_most: bool,
}

impl Line {
    pub fn margin(&self) -> f64 {
        if self.at_most {
            self.required - self.value
        } else {
            self.value - self.required
        }
    }

    pub fn passes(&self) -> bool {
        self.margin() >= 0.0
    }

    /// Whether the margin is larger than two standard errors (the verdict holds).
    pub fn certain(&self) -> bool {
        self.margin().abs() > 2.0 * self.std_error
    }
}

/// A grid's check against its activity.
#[derive(Clone, Debug)]
pub struct GridCheck {
    pub grid: String,
    pub activity: Activity,
    pub lines: Vec<Line>,
    /// What could not be checked, and why.
    pub not_checked: Vec<String>,
}

impl GridCheck {
    pub fn passes(&self) -> bool {
        self.lines.iter().all(Line::passes)
    }
}

/// The UGR judged at one of a grid's observers: (UGR, its standard error), None when no glare
/// source is seen from it, or why it could not be judged.
pub type ObserverUgr = (String, Result<Option<(f64, f64)>, String>);

/// Checks `result` (maintained values) against `activity`; `ra` is the least colour rendering
/// index the luminaires' files give (None: not given); `ugr` holds the grid's observers and
/// what glare they were judged to see.
pub fn check(
    result: &GridResult,
    activity: &Activity,
    ra: Option<f64>,
    ugr: &[ObserverUgr],
) -> GridCheck {
    let s = result.statistics();
    let [se_min, se_avg, _] = result.statistics_std_errors();
    let rel = |v: f64, se: f64| if v > 0.0 { se / v } else { 0.0 };
    let u0_se = s.u0 * (rel(s.e_min_lx, se_min).powi(2) + rel(s.e_avg_lx, se_avg).powi(2)).sqrt();
    let mut lines = vec![
        Line {
            what: "Em (maintained average, lx)".to_owned(),
            value: s.e_avg_lx,
            required: activity.em_lx,
            std_error: se_avg,
            at_most: false,
        },
        Line {
            what: "U0 = Emin / Eavg".to_owned(),
            value: s.u0,
            required: activity.u0,
            std_error: u0_se,
            at_most: false,
        },
    ];
    let mut not_checked = Vec::new();
    if let Some(limit) = activity.ugr_l {
        if ugr.is_empty() {
            not_checked.push(format!(
                "UGR (at most {limit}): the grid names no observers (observers = [...])"
            ));
        }
        for (name, judged) in ugr {
            match judged {
                Ok(Some((value, se))) => lines.push(Line {
                    what: format!("UGR at observer {name} (at most)"),
                    value: *value,
                    required: limit,
                    std_error: *se,
                    at_most: true,
                }),
                Ok(None) => not_checked.push(format!(
                    "UGR at observer {name} (at most {limit}): no glare source in view, below \
                     any limit"
                )),
                Err(e) => not_checked.push(format!("UGR at observer {name}: {e}")),
            }
        }
    }
    match (activity.ra, ra) {
        (Some(required), Some(given)) => lines.push(Line {
            what: "Ra (lamps, from the luminaire files)".to_owned(),
            value: given,
            required,
            std_error: 0.0,
            at_most: false,
        }),
        (Some(required), None) => not_checked.push(format!(
            "Ra (at least {required}): not given by the luminaire files"
        )),
        (None, _) => {}
    }
    GridCheck {
        grid: result.name.clone(),
        activity: activity.clone(),
        lines,
        not_checked,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::measure::PointResult;
    use glam::Vec3;

    fn grid(values: &[f64], se: f64) -> GridResult {
        GridResult {
            name: "desk".into(),
            normal: Vec3::Y,
            points: values
                .iter()
                .map(|&e| PointResult {
                    i: 0,
                    j: 0,
                    position: Vec3::ZERO,
                    illuminance_lx: e,
                    std_error_lx: se,
                    buried: false,
                })
                .collect(),
            samples: 64,
            rays: 0,
        }
    }

    #[test]
    fn the_shipped_table_parses_and_every_row_has_a_source() {
        let r = Requirements::parse(DEFAULT_REQUIREMENTS, "table").unwrap();
        assert!(r.activities.len() >= 5);
        for a in &r.activities {
            assert!(a.source.starts_with("EN 12464-1"), "{}", a.key);
        }
        let office = r.activity("office-writing").unwrap();
        assert_eq!(
            (office.em_lx, office.u0, office.ugr_l),
            (500.0, 0.6, Some(19.0))
        );
        let err = r.activity("kitchen").unwrap_err();
        assert!(
            err.contains("office-writing") && err.contains("corridor"),
            "{err}"
        );
        let bad = Requirements::parse("[[activity]]\nkey = 1\n", "mine.toml").unwrap_err();
        assert!(bad.starts_with("mine.toml: line 2"), "{bad}");
    }

    /// A grid built to pass (Eavg 600 lx, U0 0.83, UGR 17.2 ± 0.1 against 19) and one built
    /// to fail (Eavg 450 lx, UGR 20.5); UGR is a maximum.
    #[test]
    fn a_grid_built_to_pass_passes_and_one_built_to_fail_fails() {
        let r = Requirements::parse(DEFAULT_REQUIREMENTS, "table").unwrap();
        let office = r.activity("office-writing").unwrap();
        let pass = check(
            &grid(&[500.0, 600.0, 700.0], 5.0),
            office,
            Some(85.0),
            &[
                ("desk".into(), Ok(Some((17.2, 0.1)))),
                ("door".into(), Ok(None)),
            ],
        );
        assert!(pass.passes(), "{pass:?}");
        assert!(pass.lines.iter().all(Line::certain));
        assert!((pass.lines[0].margin() - 100.0).abs() < 1e-9);
        let ugr = pass.lines.iter().find(|l| l.at_most).unwrap();
        assert!((ugr.margin() - 1.8).abs() < 1e-9 && ugr.what.contains("desk"));
        assert_eq!(pass.not_checked.len(), 1, "{:?}", pass.not_checked);
        assert!(
            pass.not_checked[0].contains("door"),
            "{:?}",
            pass.not_checked
        );
        let glaring = check(
            &grid(&[500.0, 600.0, 700.0], 5.0),
            office,
            Some(85.0),
            &[("desk".into(), Ok(Some((20.5, 0.1))))],
        );
        assert!(!glaring.passes());
        let none = check(&grid(&[500.0, 600.0, 700.0], 5.0), office, Some(85.0), &[]);
        assert!(
            none.not_checked[0].contains("names no observers"),
            "{:?}",
            none.not_checked
        );
        let fail = check(&grid(&[400.0, 450.0, 500.0], 5.0), office, None, &[]);
        assert!(!fail.passes());
        assert!(!fail.lines[0].passes() && fail.lines[0].certain());
        assert!(fail.not_checked.iter().any(|n| n.starts_with("Ra")));
        // A margin within its uncertainty is said to be so.
        let close = check(&grid(&[499.0, 501.0, 502.0], 50.0), office, None, &[]);
        assert!(!close.lines[0].certain());
    }
}
