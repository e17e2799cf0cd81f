//! The scene reader's checks of the dynamics tables ([`dynamics::check_tables`]) and of the
//! masses only the elastic dynamics reads (`[[masses]]`, a string's `mass`), their errors
//! tied to the file and the line of the item they name.

use super::dynamics::{self, Culprit};
use super::{line_at, SceneFile};
use crate::error::{IoError, Result};
use tensegrity_core::Structure;

impl SceneFile {
    /// μ_k ≤ μ_s, no node starting below the ground, one rest-length table per string; an
    /// error names the file and the line of the node, `[ground]` or `[[actuation]]` table
    /// (`text`: the scene text; `None` for structure data, whose errors have no line).
    pub(super) fn check_dynamics(
        &self,
        structure: &Structure,
        text: Option<&str>,
        name: &str,
    ) -> Result<()> {
        for (k, table) in self.actuators.iter().enumerate() {
            // each table alone, then all of them (a rest length driven twice)
            let upto: Vec<_> = self.actuators[..=k]
                .iter()
                .map(|a| a.get_ref().clone())
                .collect();
            super::actuators(&upto, structure).map_err(|e| IoError::InScene {
                file: name.to_string(),
                line: line_at(text, table.span().start),
                source: Box::new(e),
            })?;
        }
        let actuation: Vec<_> = self.actuation.iter().map(|a| a.get_ref().clone()).collect();
        let ground = self.ground.as_ref();
        dynamics::check_tables(structure, ground.map(|g| g.get_ref()), &actuation).map_err(
            |failed| {
                let (source, culprit) = *failed;
                let start = match culprit {
                    Culprit::Node(i) => self.nodes.get(i).map(|n| n.span().start),
                    Culprit::Ground => ground.map(|g| g.span().start),
                    Culprit::Actuation(k) => self.actuation.get(k).map(|a| a.span().start),
                };
                IoError::InScene {
                    file: name.to_string(),
                    line: start.and_then(|s| line_at(text, s)),
                    source: Box::new(source),
                }
            },
        )
    }

    /// Every `[[masses]]` entry on an existing node with a mass finite and ≥ 0, and every
    /// string's `mass` finite and ≥ 0: errors name `point mass K` or `string K` and its line.
    pub(super) fn check_masses(
        &self,
        n_nodes: usize,
        text: Option<&str>,
        name: &str,
    ) -> Result<()> {
        let at = |start: usize, source: IoError| IoError::InScene {
            file: name.to_string(),
            line: line_at(text, start),
            source: Box::new(source),
        };
        let negative = |table: String, value: f64| IoError::NegativeValue {
            table,
            name: "mass",
            value,
        };
        for (k, m) in self.masses.iter().enumerate() {
            let (start, spec) = (m.span().start, m.get_ref());
            if spec.node >= n_nodes {
                let unknown = IoError::UnknownIndex {
                    table: format!("point mass {k}"),
                    kind: "node",
                    index: spec.node,
                    count: n_nodes,
                };
                return Err(at(start, unknown));
            }
            if !(spec.mass.is_finite() && spec.mass >= 0.0) {
                return Err(at(start, negative(format!("point mass {k}"), spec.mass)));
            }
        }
        for (k, st) in self.strings.iter().enumerate() {
            match st.get_ref().mass {
                Some(m) if !(m.is_finite() && m >= 0.0) => {
                    return Err(at(st.span().start, negative(format!("string {k}"), m)))
                }
                _ => {}
            }
        }
        Ok(())
    }
}
