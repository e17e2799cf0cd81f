//! The scene reader's checks of the dynamics tables ([`dynamics::check_tables`]), their
//! errors tied to the file and the line of the item they name.

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
}
