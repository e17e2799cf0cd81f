//! Design files of inverse form-finding: a topology file ([`crate::topology`]: nodes,
//! members with their start force densities, groups, held nodes, loads) with a `[design]`
//! table, read into a [`formfind::Topology`] and a [`DesignSpec`] (`formfind::design`: what
//! each key means).
//!
//! ```toml
//! # … the topology: [[strings]], [[bars]], [groups.NAME], [[fixed]], [[loads]], nodes …
//! [design.optimizer]               # optional: max_iterations (1000), ftol (2.2e-9),
//! max_iterations = 500             # gtol (1e-5), memory (10)
//!
//! [[design.parameters]]            # optional (default: every member's q, a group's shared)
//! select = "strings"               # or members = [0, 1, 2] (shared = true: one q), or
//! lower = 0.1                      # group = "edge"; lower / upper bounds in N/m (a bar's
//!                                  # q stays ≤ 0, a string's ≥ 0)
//! [[design.terms]]
//! name = "edge force"              # optional
//! error = "mean_squared"           # squared (default), mean_squared, root_mean_squared,
//! weight = 1.0                     # absolute, mean_absolute, prediction, mean_prediction
//! [[design.terms.goals]]
//! kind = "force"                   # position, coordinate, plane, line, length, force,
//! members = [0, 1, 2]              # direction, force_density, reaction, reaction_force,
//!                                  # reaction_limit, load_path, smoothness
//! target = 20.0                    # or targets = [...], one per member or node
//! weight = 1.0
//! ```
//!
//! Positions, coordinates, smoothness and reactions take `nodes` (default: the free nodes, the
//! held ones for reactions), the member goals `members` or `group` (default: every member); a
//! position goal without a target aims at the file's own `nodes` (shape matching); a
//! `coordinate` takes `axis` (0, 1, 2) and a number as its target, `plane` a `point` and a
//! `normal`, `line` a `point` and a `direction`; `reaction_limit` takes `limit` (N). Unknown keys are refused with the line; what the keys name (a member,
//! node or group the topology lacks, a target count that does not match) is checked by
//! [`formfind::design::design`], naming the item (`design.terms[0].goals[1].members`).
//!
//! ```
//! let text = "[[strings]]\nnodes = [0, 1]\nforce_density = 1.0\n\
//!             [[fixed]]\nnode = 0\nposition = [0.0, 0.0, 0.0]\n\
//!             [[loads]]\nnode = 1\nforce = [1.0, 0.0, 0.0]\n\
//!             [[design.terms]]\n[[design.terms.goals]]\nkind = \"length\"\ntarget = 2.0\n";
//! let (t, spec) = tensegrity_io::design::from_str_named(text, "pull.toml")?;
//! assert_eq!(t.strings.len(), 1);
//! let d = formfind::design::design(&t, &spec).unwrap();
//! // a 1 N pull on a string of force density q has length 1 / q
//! assert!((d.force_density[0] - 0.5).abs() < 1e-5, "{:?}", d.force_density);
//! let bad = text.replace("target = 2.0", "target = 2.0\ntargte = 1.0");
//! let e = tensegrity_io::design::from_str_named(&bad, "pull.toml").unwrap_err().to_string();
//! assert!(e.contains("pull.toml") && e.contains("line 11") && e.contains("targte"), "{e}");
//! # Ok::<(), tensegrity_io::IoError>(())
//! ```

use crate::error::{IoError, Result};
use formfind::design::DesignSpec;
use formfind::Topology;
use serde::Deserialize;
use std::path::Path;

/// The `[design]` table of a file, the rest of it read as the topology.
#[derive(Deserialize)]
struct DesignFile {
    design: Option<DesignSpec>,
    #[serde(flatten)]
    _rest: toml::Table,
}

/// Reads a design file (at most [`crate::read::MAX_SCENE_BYTES`]): its topology and its
/// design problem; errors name the file, the line and the item.
pub fn from_path(path: &Path) -> Result<(Topology, DesignSpec)> {
    let text = crate::read::read_text(path, crate::read::MAX_SCENE_BYTES, "a design file")?;
    from_str_named(&text, &path.display().to_string())
}

/// Parses a design file's text; `name` labels the errors (module docs). A file without a
/// `[design]` table is refused: it is a topology only.
pub fn from_str_named(text: &str, name: &str) -> Result<(Topology, DesignSpec)> {
    let topology = crate::topology::from_str_named(text, name)?;
    let file: DesignFile = crate::topology::parse(text, name)?;
    let spec = file.design.ok_or_else(|| IoError::InvalidTopology {
        file: name.to_string(),
        line: None,
        source: Box::new(formfind::FormFindError::InvalidTopology {
            item: "design".into(),
            reason: "no [design] table: give the parameters, terms and goals of the design \
                     (the topology alone is `tensegrity formfind`'s)"
                .into(),
        }),
    })?;
    Ok((topology, spec))
}
