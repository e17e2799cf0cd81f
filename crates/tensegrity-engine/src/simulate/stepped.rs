//! A scene as a stepped simulation ([`Stepper`]): the scene read and its run set up exactly
//! as `simulate` does (the request's overrides over the scene's `[simulation]`, its ground and
//! actuation tables), its `[[actuators]]` the actuators. The control tick is the run's `dt`:
//! given, else the scene's, else the integrator's default step (adaptive methods:
//! [`ADAPTIVE_TICK`]). The end time is not read (a stepped run ends when its caller stops).

use super::{default_step, SimulateCommand};
use crate::scene::SceneError;
use tensegrity_core::request::InvalidParameter;
use tensegrity_dynamics::Stepper;
use tensegrity_io::scene::Scene;

/// The control tick (s) of an adaptive integrator with no step given: its largest step and
/// the period an action lasts per step count.
pub const ADAPTIVE_TICK: f64 = 1e-2;

/// The stepped simulation of the request's scene, and the scene (its structure labels the
/// observations). Elastic scenes are refused (the stepped simulation steps rigid bars).
pub fn stepper(command: &SimulateCommand) -> Result<(Scene, Stepper), SceneError> {
    let scene = command.source()?.load()?;
    stepper_of(command, scene)
}

/// [`stepper`] of a scene already read.
pub fn stepper_of(command: &SimulateCommand, scene: Scene) -> Result<(Scene, Stepper), SceneError> {
    if super::elastic::is_elastic(&scene) {
        return Err(InvalidParameter::raw(
            "scene",
            "elastic bars",
            "a stepped simulation steps the rigid-bar dynamics: give the scene rigid bars (no `[simulation] bars = \"elastic\"` or bar `elastic = true`)",
        )
        .into());
    }
    let mut command = command.clone();
    // the end time is not read; the tick is always set
    command.t_end = command.t_end.or(Some(1.0));
    let file = scene.file.simulation.as_ref();
    let kind = command
        .integrator
        .or(file.map(|s| s.integrator))
        .unwrap_or_default();
    if command.dt.is_none() && file.and_then(|s| s.dt).is_none() {
        command.dt = Some(default_step(kind).unwrap_or(ADAPTIVE_TICK));
    }
    let (scene, simulation) = command.prepare_scene(scene, false)?;
    let actuators = scene.actuators()?;
    let stepper = Stepper::new(simulation, actuators)?;
    Ok((scene, stepper))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneSource;
    use tensegrity_dynamics::{Action, ActuatorTarget, IntegratorKind};

    /// A bar hanging by a string from a pinned node (the scene's lines 1 to 9).
    const BAR_ON_A_STRING: &str = "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\n\
                                   [[bars]]\nnodes = [0, 1]\nmass = 1.0\n\
                                   [[strings]]\nnodes = [1, 2]\nstiffness = 10.0\n\
                                   [[supports]]\nnode = 2\n";

    fn command(scene: SceneSource) -> SimulateCommand {
        SimulateCommand {
            scene: Some(scene),
            ..Default::default()
        }
    }

    #[test]
    fn the_superball_scene_steps_with_its_actuator_limits() {
        let c = command(SceneSource::parse("../../examples/robots/superball.toml"));
        let (scene, mut st) = stepper(&c).unwrap();
        assert_eq!(scene.structure.n_strings(), 24);
        assert_eq!(st.actuators().len(), 24);
        let a = st.actuators()[23];
        assert_eq!(a.target, ActuatorTarget::String(23));
        assert_eq!((a.min_length, a.max_length, a.max_rate), (0.5, 1.1, 0.5));
        assert_eq!(st.dt(), 1e-3);
        // a pull past the limits: 20 ms at 0.5 m/s
        let r0 = st.rest_lengths()[0];
        st.step(Action::RestLengths(&[0.0; 24]), 20).unwrap();
        assert!((st.rest_lengths()[0] - (r0 - 0.01)).abs() < 1e-12);
    }

    #[test]
    fn a_scene_without_a_step_or_tables_gets_a_tick_and_every_string() {
        let mut c = command(SceneSource::parse(BAR_ON_A_STRING));
        let (_, st) = stepper(&c).unwrap();
        assert_eq!((st.dt(), st.actuators().len()), (1e-3, 1));
        c.integrator = Some(IntegratorKind::Rk45);
        let (_, st) = stepper(&c).unwrap();
        assert_eq!(st.dt(), ADAPTIVE_TICK);
    }

    #[test]
    fn bad_actuator_tables_and_elastic_scenes_are_named() {
        let base = BAR_ON_A_STRING;
        let cases = [
            (
                "[[actuators]]\nstring = 4\n",
                "actuators 0: string 4 does not exist",
            ),
            (
                "[[actuators]]\nstring = 0\nmin_length = 2.0\nmax_length = 1.0\n",
                "max_length must be finite and ≥ min_length",
            ),
            (
                "[[actuators]]\nstring = 0\n[[actuators]]\nstrings = [0]\n",
                "actuators 1: a rest length it names is driven by another actuator",
            ),
            ("[[actuators]]\nmax_rate = 1.0\n", "give one of `string`"),
            (
                "[[actuators]]\nstring = 0\nmax_rate = -1.0\n",
                "max_rate must be positive",
            ),
            (
                "[[actuators]]\nstring = 0\nmin_length = 5.0\n",
                "actuator 0: its initial rest length",
            ),
            (
                "[simulation]\nt_end = 1.0\nbars = \"elastic\"\n",
                "elastic bars",
            ),
        ];
        for (extra, expected) in cases {
            let c = command(SceneSource::parse(&format!("{base}{extra}")));
            let e = stepper(&c).unwrap_err().to_string();
            assert!(e.contains(expected), "{extra}: {e}");
        }
        // a table's error names its line
        let c = command(SceneSource::parse(&format!(
            "{base}[[actuators]]\nstring = 9\n"
        )));
        let e = stepper(&c).unwrap_err().to_string();
        assert!(e.contains("line 10"), "{e}");
    }
}
