//! The observer hook: it sees every sample and frame as the run makes them, and a stop after
//! k samples returns exactly those k samples, `stopped_at`, an interruption warning and a run
//! that is not valid — never an error.

use wheel_rolling::{
    roll_wheel, Fidelity, FidelityChoice, Flow, Observer, Polygon, RigidRolling, RollingSample,
    RunSpec, WheelFrame,
};

/// Stops after `k` samples; keeps what it saw.
struct StopAfter {
    k: usize,
    samples: Vec<RollingSample>,
    frames: Vec<f64>,
}

impl Observer for StopAfter {
    fn sample(&mut self, s: &RollingSample) -> Flow {
        self.samples.push(*s);
        if self.samples.len() >= self.k {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }

    fn frame(&mut self, f: &WheelFrame) -> Flow {
        self.frames.push(f.t);
        Flow::Continue
    }
}

fn octagon() -> Polygon {
    Polygon {
        sides: 8,
        outer_radius: 1.0,
        mass: 12.0,
        i1: 7.5,
    }
}

fn rigid_spec(t_end: f64) -> RunSpec {
    RunSpec {
        fidelity: FidelityChoice::Rigid,
        t_end,
        ..RunSpec::default()
    }
}

#[test]
fn a_rigid_run_stopped_after_k_samples_returns_them_flagged() {
    let mut obs = StopAfter {
        k: 250,
        samples: Vec::new(),
        frames: Vec::new(),
    };
    let pose = [nalgebra::Vector3::new(0.0, 0.0, -1.0)];
    let model = RigidRolling::new(&octagon(), &rigid_spec(2.0));
    let run = model
        .run_observed(2.0, &pose, &[0.1, 0.2, 1.5], Some(&mut obs))
        .unwrap();
    let r = &run.result;
    assert_eq!(r.samples.len(), 250);
    assert_eq!(r.samples, obs.samples);
    // samples every 1 ms from 0: the 250th is at 0.249 s
    let t = r.samples[249].t;
    assert!((t - 0.249).abs() < 1e-12, "{t}");
    assert_eq!(r.validity.stopped_at, Some(t));
    assert!(!r.validity.valid());
    assert!(
        r.validity
            .warnings
            .iter()
            .any(|w| w.kind() == "interrupted" && !w.to_string().contains("--")),
        "{:?}",
        r.validity.warnings
    );
    // the frames up to the stop were handed over and kept; none after it
    assert_eq!(obs.frames, [0.1, 0.2]);
    assert_eq!(run.frames.len(), 2);
    // what was computed is the uninterrupted run's beginning, bit for bit
    let whole = model.run(2.0).unwrap();
    assert_eq!(&whole.samples[..250], &r.samples[..]);
    assert_eq!(whole.validity.stopped_at, None);
}

#[test]
fn an_observer_that_never_stops_sees_the_whole_run() {
    let mut obs = StopAfter {
        k: usize::MAX,
        samples: Vec::new(),
        frames: Vec::new(),
    };
    let r = roll_wheel(&octagon(), &rigid_spec(1.0), &[], Some(&mut obs)).unwrap();
    assert_eq!(r.fidelity, Fidelity::Rigid);
    assert_eq!(obs.samples, r.result.samples);
    assert_eq!(obs.samples.len(), 1001);
    assert!(
        r.result.validity.valid(),
        "{:?}",
        r.result.validity.warnings
    );
}

#[test]
fn auto_on_a_stiff_wheel_shows_the_observer_one_model() {
    // stiff strings (m g / (k R_o) = 5.9·10⁻⁵): the rigid run is probed unobserved; where
    // the fidelity table says the models agree on its class it is the answer and is run
    // again for the observer, which sees that run only; elsewhere the full model runs (a
    // bare polygon has none: a named error) and the observer saw nothing of the probe
    let mut spec = rigid_spec(0.5);
    spec.fidelity = FidelityChoice::Auto;
    spec.settings.string_stiffness = 2e6;
    let mut obs = StopAfter {
        k: usize::MAX,
        samples: Vec::new(),
        frames: Vec::new(),
    };
    let probe = wheel_rolling::RigidRolling::new(&octagon(), &spec)
        .run(0.5)
        .unwrap();
    let decision = wheel_rolling::Decision::of(&spec, &octagon());
    let ground = spec.settings.ground_stiffness;
    match roll_wheel(&octagon(), &spec, &[], Some(&mut obs)) {
        Ok(r) => {
            assert!(decision.rigid_answers(&probe, ground), "{}", r.reason);
            assert_eq!(r.fidelity, Fidelity::Rigid);
            assert!(r.reason.contains("rigid run is valid"), "{}", r.reason);
            assert_eq!(obs.samples, r.result.samples);
        }
        Err(e) => {
            assert!(!decision.rigid_answers(&probe, ground));
            assert!(e.to_string().contains("no full model"), "{e}");
            assert!(obs.samples.is_empty());
        }
    }
    // a bare polygon has no full model: asking for it is a named error
    spec.fidelity = FidelityChoice::Full;
    let e = roll_wheel(&octagon(), &spec, &[], None).unwrap_err();
    assert!(e.to_string().contains("no full model"), "{e}");
}

/// Streams the frames elsewhere: the run keeps none of them.
struct Streams {
    frames: Vec<WheelFrame>,
}

impl Observer for Streams {
    fn frame(&mut self, f: &WheelFrame) -> Flow {
        self.frames.push(f.clone());
        Flow::Continue
    }

    fn keeps_frames(&self) -> bool {
        false
    }
}

#[test]
fn an_observer_that_streams_the_frames_gets_them_all_and_the_run_keeps_none() {
    let pose = [nalgebra::Vector3::new(0.0, 0.0, -1.0)];
    let times: Vec<f64> = (0..=20).map(|k| 0.05 * k as f64).collect();
    let model = RigidRolling::new(&octagon(), &rigid_spec(1.0));
    let kept = model.run_observed(1.0, &pose, &times, None).unwrap();
    let mut obs = Streams { frames: Vec::new() };
    let streamed = model
        .run_observed(1.0, &pose, &times, Some(&mut obs))
        .unwrap();
    assert_eq!(kept.frames.len(), 21);
    // the same frames, bit for bit, handed over instead of kept; the same samples
    assert_eq!(obs.frames, kept.frames);
    assert!(streamed.frames.is_empty());
    assert_eq!(streamed.result, kept.result);
}

/// Lets the run go on for `polls` checks (an interrupt arriving then), sees nothing else.
struct InterruptAfter {
    polls: usize,
    samples: usize,
}

impl Observer for InterruptAfter {
    fn sample(&mut self, _: &RollingSample) -> Flow {
        self.samples += 1;
        Flow::Continue
    }

    fn keep_going(&mut self) -> bool {
        self.polls = self.polls.saturating_sub(1);
        self.polls > 0
    }
}

#[test]
fn an_interrupt_during_the_probe_of_auto_ends_the_run_with_the_probe_so_far() {
    // the probe is unobserved, but an interrupt stops it: its 100 samples are the (rigid,
    // stopped) result, and no second run follows (a bare polygon has no full model to try)
    let mut spec = rigid_spec(5.0);
    spec.fidelity = FidelityChoice::Auto;
    spec.settings.string_stiffness = 2e6;
    let mut obs = InterruptAfter {
        polls: 100,
        samples: 0,
    };
    let r = roll_wheel(&octagon(), &spec, &[], Some(&mut obs)).unwrap();
    assert_eq!(r.fidelity, Fidelity::Rigid);
    assert_eq!(obs.samples, 0, "the observer saw nothing of the probe");
    let samples = &r.result.samples;
    assert_eq!(samples.len(), 100);
    assert_eq!(r.result.validity.stopped_at, Some(samples[99].t));
    assert!(!r.result.validity.valid());
}
