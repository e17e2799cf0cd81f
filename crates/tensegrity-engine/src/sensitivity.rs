//! Sensitivities of a scene's dynamics and system identification from a measured motion, for
//! a front end (Python's `tensegrity.trajectory_sensitivity` and `tensegrity.identify`): the
//! scene read here (its structure and `[ground]`), then the library's
//! [`tensegrity_dynamics::sensitivity::forward_sensitivities`] and
//! [`tensegrity_dynamics::identify::identify`]. What the rigid-bar model of those calls does
//! not take is refused by name rather than ignored: `[[actuation]]` tables (their schedules are
//! not differentiated), elastic bars, a load path's drivers and clustered strings.
//!
//! A parameter is named as a front end gives it: `("stiffness", j)`, `("damping", j)`,
//! `("rest_length", j)` for string j, `("mass", k)` for bar k, and `("initial_position", k,
//! axis)`, `("initial_velocity", k, axis)` for bar k ([`parameter`]).

use crate::scene::{SceneError, SceneSource};
use tensegrity_core::error::DynamicsError;
use tensegrity_core::{CoreError, Structure};
use tensegrity_dynamics::sensitivity::DynamicsParameter;
use tensegrity_dynamics::Ground;

pub use tensegrity_dynamics::identify::{identify, Identified, IdentifySettings};
pub use tensegrity_dynamics::sensitivity::{forward_sensitivities, TrajectorySensitivity};

fn unsupported(item: impl Into<String>, reason: impl Into<String>) -> SceneError {
    SceneError::Core(CoreError::from(DynamicsError::Unsupported {
        item: item.into(),
        reason: reason.into(),
    }))
}

/// The structure and ground of a scene for the sensitivities (module docs: what is refused).
///
/// ```
/// use tensegrity_engine::sensitivity::scene_dynamics;
/// use tensegrity_engine::SceneSource;
/// let text = "nodes = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [2.0, 0.0, 1.0]]\n\
///             [[bars]]\nnodes = [0, 1]\nmass = 1.0\n\
///             [[strings]]\nnodes = [1, 2]\nstiffness = 100.0\n[[supports]]\nnode = 2\n\
///             [ground]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nmodel = \"penalty\"\n\
///             stiffness = 1e4\n";
/// let (s, ground) = scene_dynamics(&SceneSource::parse(text)).unwrap();
/// assert_eq!((s.n_bars(), s.n_strings()), (1, 1));
/// assert!(ground.is_some());
/// let acted = format!("{text}[[actuation]]\nstring = 0\ntimes = [0.0, 1.0]\nrest_lengths = [1.0, 0.9]\n");
/// let e = scene_dynamics(&SceneSource::parse(&acted)).unwrap_err().to_string();
/// assert!(e.contains("do not differentiate [[actuation]]"), "{e}");
/// ```
pub fn scene_dynamics(source: &SceneSource) -> Result<(Structure, Option<Ground>), SceneError> {
    let scene = source.load()?;
    let name = source.as_str().to_string();
    if !scene.file.actuation.is_empty() {
        return Err(unsupported(
            format!("{name}: actuation"),
            "the sensitivities do not differentiate [[actuation]] schedules yet: remove them (a constant rest length is the parameter `rest_length`)",
        ));
    }
    if scene.file.is_elastic() {
        return Err(unsupported(
            format!("{name}: simulation.bars"),
            "the sensitivities are those of the rigid-bar dynamics: elastic bars are not differentiated",
        ));
    }
    if let Some(key) = scene.file.path_keys().first() {
        return Err(unsupported(
            format!("{name}: {key}"),
            "a load path's key: `solve` reads it",
        ));
    }
    if !scene.structure.clusters().is_empty() {
        return Err(unsupported(
            format!("{name}: clusters"),
            "clustered strings are not differentiated yet",
        ));
    }
    let ground = match &scene.file.ground {
        Some(g) => Some(g.get_ref().to_ground()?),
        None => None,
    };
    Ok((scene.structure, ground))
}

/// The parameter a front end names (module docs); an unknown kind is the error, naming it.
///
/// ```
/// use tensegrity_engine::sensitivity::parameter;
/// use tensegrity_dynamics::sensitivity::DynamicsParameter;
/// assert_eq!(parameter("damping", 3, 0).unwrap(), DynamicsParameter::Damping(3));
/// assert!(parameter("spring", 3, 0).is_err());
/// ```
pub fn parameter(kind: &str, index: usize, axis: usize) -> Result<DynamicsParameter, SceneError> {
    Ok(match kind {
        "stiffness" => DynamicsParameter::Stiffness(index),
        "damping" => DynamicsParameter::Damping(index),
        "rest_length" => DynamicsParameter::RestLength(index),
        "mass" => DynamicsParameter::BarMass(index),
        "initial_position" => DynamicsParameter::InitialPosition { bar: index, axis },
        "initial_velocity" => DynamicsParameter::InitialVelocity { bar: index, axis },
        other => {
            return Err(unsupported(
                format!("parameter {other:?}"),
                "one of stiffness, damping, rest_length (a string's), mass, initial_position, initial_velocity (a bar's)",
            ))
        }
    })
}
