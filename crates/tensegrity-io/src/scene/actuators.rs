//! The `[[actuators]]` tables of a scene: which rest lengths a controller of a stepped
//! simulation sets ([`tensegrity_dynamics::Stepper`]) and their limits.
//!
//! ```toml
//! [[actuators]]                 # one string
//! string = 3
//! min_length = 0.2              # m, default 0
//! max_length = 1.5              # m, default none
//! max_rate = 0.1                # m/s, default none
//!
//! [[actuators]]                 # several strings with the same limits, one actuator each
//! strings = [0, 1, 2]
//! max_rate = 0.1
//!
//! [[actuators]]                 # a clustered string's whole rest length
//! cluster = 0
//! ```
//!
//! Without `[[actuators]]` every string, then every cluster, is an actuator without limits
//! (in the structure's order). The actuators are numbered in the order of the tables (a
//! `strings` list in its order); the limits must satisfy 0 ≤ `min_length` ≤ `max_length`
//! and `max_rate` > 0, and each rest length is driven once.

use crate::error::{IoError, Result};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use tensegrity_core::Structure;
use tensegrity_dynamics::Actuator;

/// One `[[actuators]]` table.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ActuatorSpec {
    /// One string.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub string: Option<usize>,
    /// Several strings with the same limits (one actuator each).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub strings: Option<Vec<usize>>,
    /// A clustered string (its whole rest length).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cluster: Option<usize>,
    /// Shortest rest length (m), default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_length: Option<f64>,
    /// Longest rest length (m), default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_length: Option<f64>,
    /// Fastest change of the rest length (m/s), default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_rate: Option<f64>,
}

fn invalid(k: usize, reason: &'static str) -> IoError {
    IoError::InvalidTable {
        table: format!("actuators {k}"),
        reason,
    }
}

impl ActuatorSpec {
    /// The actuators of table `k` of `structure`, checked: one of `string`, `strings`,
    /// `cluster`; existing members; ordered, finite limits.
    fn actuators(&self, k: usize, structure: &Structure) -> Result<Vec<Actuator>> {
        let unknown = |kind, index, count| IoError::UnknownIndex {
            table: format!("actuators {k}"),
            kind,
            index,
            count,
        };
        let (n_s, n_c) = (structure.n_strings(), structure.clusters().len());
        let bare: Vec<Actuator> = match (self.string, &self.strings, self.cluster) {
            (Some(s), None, None) => vec![Actuator::string(s)],
            (None, Some(list), None) if !list.is_empty() => {
                list.iter().map(|&s| Actuator::string(s)).collect()
            }
            (None, None, Some(c)) if c < n_c => vec![Actuator::cluster(c)],
            (None, None, Some(c)) => return Err(unknown("cluster", c, n_c)),
            _ => {
                return Err(invalid(
                    k,
                    "give one of `string`, `strings` (a non-empty list) or `cluster`",
                ))
            }
        };
        let named = [self.string]
            .into_iter()
            .flatten()
            .chain(self.strings.iter().flatten().copied());
        if let Some(s) = named.into_iter().find(|&s| s >= n_s) {
            return Err(unknown("string", s, n_s));
        }
        let lo = self.min_length.unwrap_or(0.0);
        let hi = self.max_length.unwrap_or(f64::INFINITY);
        let rate = self.max_rate.unwrap_or(f64::INFINITY);
        if !(lo.is_finite() && lo >= 0.0) {
            return Err(invalid(k, "min_length must be finite and ≥ 0"));
        }
        if hi.is_nan() || hi < lo || self.max_length.is_some_and(|m| !m.is_finite()) {
            return Err(invalid(k, "max_length must be finite and ≥ min_length"));
        }
        if self.max_rate.is_some_and(|r| !(r.is_finite() && r > 0.0)) {
            return Err(invalid(k, "max_rate must be positive and finite"));
        }
        Ok(bare
            .into_iter()
            .map(|a| a.min_length(lo).max_length(hi).max_rate(rate))
            .collect())
    }
}

/// The actuators of `tables` on `structure` (module docs: every string then every cluster
/// when there is no table); `Err` names the table.
///
/// ```
/// use tensegrity_core::{Bar, StringMember, Structure};
/// use tensegrity_io::scene::{actuators, ActuatorSpec};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
///     .bar(Bar::new(0, 1).mass(1.0))
///     .string(StringMember::new(1, 2).stiffness(10.0))
///     .string(StringMember::new(2, 0).stiffness(10.0))
///     .build()?;
/// assert_eq!(actuators(&[], &s)?.len(), 2);
/// let t: ActuatorSpec = toml::from_str("strings = [1]\nmax_rate = 0.5")?;
/// assert_eq!(actuators(&[t], &s)?[0].max_rate, 0.5);
/// let bad: ActuatorSpec = toml::from_str("string = 7")?;
/// assert!(actuators(&[bad], &s).unwrap_err().to_string().contains("actuators 0: string 7"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn actuators(tables: &[ActuatorSpec], structure: &Structure) -> Result<Vec<Actuator>> {
    if tables.is_empty() {
        let strings = (0..structure.n_strings()).map(Actuator::string);
        let clusters = (0..structure.clusters().len()).map(Actuator::cluster);
        return Ok(strings.chain(clusters).collect());
    }
    let mut out: Vec<Actuator> = Vec::new();
    for (k, t) in tables.iter().enumerate() {
        for a in t.actuators(k, structure)? {
            if out.iter().any(|b| b.target == a.target) {
                return Err(invalid(
                    k,
                    "a rest length it names is driven by another actuator: drive each once",
                ));
            }
            out.push(a);
        }
    }
    Ok(out)
}
