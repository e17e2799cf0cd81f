//! The anchor scenes of `examples/anchors/` as benchmark data: each scene's TOML (built into
//! the library, so the benchmark runs from any directory), the reference final state of its
//! independent integrator (`tests/anchors.rs`: shared nodes, bar lengths as Lagrange
//! constraints, RK4 at a tenth of the step), the tolerance our run at the scene's step meets
//! against it, and the reference code's time for the same run.
//!
//! The reference times were measured on 2026-11-28 on the project's machine kind (issue 25:
//! MOTES and TsgFEM under GNU Octave 7.3, best of 5 interleaved rounds, whole-process CPU),
//! not in the benchmark's run: a ratio of one of them to a time measured here and now would
//! compare two machines, or one machine under two loads (it once read 1,445× for the D-bar
//! where the same codes side by side gave 6,000×). So the report gives them with their date
//! and machine ([`MEASURED_ON`], [`ReferenceTime::measured`]) and no ratio; the ratios of
//! side-by-side runs are in docs/notes/PERFORMANCE.md with the commands that made them.

use serde::Serialize;
use std::fmt;
use std::str::FromStr;
use tensegrity_dynamics::SimulationResult;
use tensegrity_engine::scene::SceneError;
use tensegrity_io::scene::Scene;

/// The label of every reference time.
pub const MEASURED_ON: &str = "reference times: MOTES and TsgFEM under GNU Octave 7.3, best of 5 rounds, whole-process CPU, stored: measured on 2026-11-28 on the project's 2-core machine kind, not in this run, so no ratio is formed from them (side-by-side ratios: docs/notes/PERFORMANCE.md)";

/// When and where the stored reference times were measured.
pub const REFERENCE_MEASURED: &str = "2026-11-28, the project's 2-core machine kind (issue 25)";

/// The runtime of the reference codes.
pub const REFERENCE_RUNTIME: &str = "GNU Octave 7.3";

/// One anchor scene (serialised as its name, [`Anchor::name`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Anchor {
    /// The MOTES square D-bar (4 bars, 2 strings, class-2 joints, a pin), RK4, 5000 steps.
    MotesDbar,
    /// The 3-bar prism with massless strings, free, RK4, 5000 steps.
    MotesPrism,
    /// The TsgFEM planar T-bar with tension-only strings under a step load, RK4, 2000 steps.
    TsgfemTbar,
    /// The compound double pendulum, RK4, 5000 steps.
    #[serde(rename = "double_pendulum_rk4")]
    DoublePendulum,
}

/// A reference code's time for an anchor's whole run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReferenceTime {
    /// The code (MOTES, TsgFEM).
    pub code: &'static str,
    /// Its time for the scene's run (s), stored ([`MEASURED_ON`]).
    pub seconds: f64,
    /// When and where it was measured ([`REFERENCE_MEASURED`]): not in this run.
    pub measured: &'static str,
}

impl Anchor {
    /// Every anchor, in the order of the report.
    pub const ALL: [Anchor; 4] = [
        Anchor::MotesDbar,
        Anchor::MotesPrism,
        Anchor::TsgfemTbar,
        Anchor::DoublePendulum,
    ];

    /// The name (the scene file's stem).
    pub fn name(self) -> &'static str {
        match self {
            Anchor::MotesDbar => "motes_dbar",
            Anchor::MotesPrism => "motes_prism",
            Anchor::TsgfemTbar => "tsgfem_tbar",
            Anchor::DoublePendulum => "double_pendulum_rk4",
        }
    }

    /// The scene file in the repository.
    pub fn path(self) -> String {
        format!("examples/anchors/{}.toml", self.name())
    }

    /// The scene's TOML text (the file, built in).
    pub fn toml(self) -> &'static str {
        match self {
            Anchor::MotesDbar => include_str!("../../../examples/anchors/motes_dbar.toml"),
            Anchor::MotesPrism => include_str!("../../../examples/anchors/motes_prism.toml"),
            Anchor::TsgfemTbar => include_str!("../../../examples/anchors/tsgfem_tbar.toml"),
            Anchor::DoublePendulum => {
                include_str!("../../../examples/anchors/double_pendulum_rk4.toml")
            }
        }
    }

    /// The reference code's time (module docs).
    pub fn reference(self) -> ReferenceTime {
        let (code, seconds) = match self {
            Anchor::MotesDbar => ("MOTES", 54.3),
            Anchor::MotesPrism => ("MOTES", 12.3),
            Anchor::TsgfemTbar => ("TsgFEM", 2.75),
            Anchor::DoublePendulum => ("MOTES", 35.1),
        };
        ReferenceTime {
            code,
            seconds,
            measured: REFERENCE_MEASURED,
        }
    }

    /// The final nodes of the independent integrator (`tests/anchors.rs`, RK4 at a tenth of
    /// the scene's step; the pendulum's tip is the published one).
    pub fn reference_final_nodes(self) -> &'static [[f64; 3]] {
        match self {
            Anchor::MotesDbar => &REFERENCE_MOTES_DBAR,
            Anchor::MotesPrism => &REFERENCE_MOTES_PRISM,
            Anchor::TsgfemTbar => &REFERENCE_TSGFEM_TBAR,
            Anchor::DoublePendulum => &REFERENCE_DOUBLE_PENDULUM,
        }
    }

    /// How far (m, largest coordinate) the run at the scene's step may land from
    /// [`Anchor::reference_final_nodes`]: the RK4 error at that step (`tests/anchors.rs`).
    pub fn tolerance(self) -> f64 {
        match self {
            // string 0-2 goes slack (a kink in the force)
            Anchor::MotesDbar => 2e-6,
            Anchor::MotesPrism => 1e-7,
            Anchor::TsgfemTbar => 5e-8,
            Anchor::DoublePendulum => 5e-9,
        }
    }

    /// The scene, read from the built-in text (errors name the scene file).
    pub fn scene(self) -> Result<Scene, SceneError> {
        Ok(Scene::from_str_named(self.toml(), &self.path())?)
    }

    /// Runs the scene as `tensegrity simulate` does without outputs or convergence check;
    /// with `steps`, only the first `steps` steps (t_end = steps · dt).
    pub fn run(self, steps: Option<u64>) -> Result<SimulationResult, SceneError> {
        let mut simulation = self.scene()?.simulation()?;
        if let Some(k) = steps {
            simulation.settings.t_end = k as f64 * simulation.settings.dt;
        }
        Ok(simulation.run()?)
    }
}

impl fmt::Display for Anchor {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Anchor {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Anchor::ALL
            .into_iter()
            .find(|a| a.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Anchor::ALL.iter().map(|a| a.name()).collect();
                format!("unknown anchor `{s}` (one of {})", names.join(", "))
            })
    }
}

/// Final nodes of the MOTES D-bar at t = 5 s.
const REFERENCE_MOTES_DBAR: [[f64; 3]; 4] = [
    [-1.0, 0.0, 0.0],
    [-0.802251287978851, -1.4003197659441746, 0.0],
    [-0.6045025759579379, -1.7562077706334087e-14, 0.0],
    [-0.8022512879788818, 1.4003197659441213, 0.0],
];
/// Final nodes of the prism at t = 5 s.
const REFERENCE_MOTES_PRISM: [[f64; 3]; 6] = [
    [
        0.9963498821440334,
        -0.0070183114385637905,
        -0.001648209363452766,
    ],
    [
        -0.49209690507454135,
        0.8663734647136662,
        -0.001648209363428303,
    ],
    [
        -0.5042529770694993,
        -0.8593551532750594,
        -0.001648209363423855,
    ],
    [0.8593551532750725, 0.5042529770695015, 2.0016482093633945],
    [-0.8663734647136557, 0.4920969050745413, 2.0016482093634127],
    [
        0.007018311438577982,
        -0.9963498821440276,
        2.0016482093634207,
    ],
];
/// Final nodes of the T-bar at t = 2 s.
const REFERENCE_TSGFEM_TBAR: [[f64; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.9975627266439149, 0.0, 0.0],
    [0.9987813633219558, -0.0493537058458872, 0.0],
    [0.9984600220132863, 0.45064619089384395, 0.0],
    [0.9986165825773048, -0.5493536786931973, 0.0],
];
/// Final nodes of the double pendulum at t = 5 s.
const REFERENCE_DOUBLE_PENDULUM: [[f64; 3]; 3] = [
    [0.0, 0.0, 0.0],
    [0.6246646016257225, -0.7808931652126023, 0.0],
    [1.3403149308132003, -1.479351901526694, 0.0],
];
