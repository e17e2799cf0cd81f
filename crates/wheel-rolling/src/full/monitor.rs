//! The full model's step monitor: it sees every integration step of a rolling run (as a
//! streaming [`SampleSink`]) and keeps the 1 ms samples, the requested node frames, the
//! validity figures, the energy budget and the impact log (equations in the parent module);
//! it hands each sample and frame to the run's observer as it keeps it.

use super::scene::WheelScene;
use super::FullRun;
use crate::contact::contact_effective_mass;
use crate::defaults;
use crate::frame::WheelFrame;
use crate::observer::{Flow, Observer};
use crate::sample::{summarise, RollingSample};
use crate::validity::{ImpactRecord, RollValidity};
use nalgebra::Vector3;
use std::f64::consts::PI;
use tensegrity_core::CoreError;
use tensegrity_core::Warning;
use tensegrity_dynamics::{Sample, SampleSink};

/// What the monitor needs of the wheel and the slope.
pub(super) struct Geometry {
    /// Number of contact groups (sides of the contact polygon).
    n: usize,
    /// Outer radius R_o (m).
    r_o: f64,
    /// The nodes whose mean spin about the hub is ω (the toroid: the rim joints n3).
    rim: Vec<usize>,
    /// Axle end nodes, if any.
    axle: Option<[usize; 2]>,
    /// The contact group of every node (None: it cannot touch the slope).
    group: Vec<Option<usize>>,
    /// y of the starting downhill pair, R_o sin(π/n) (m).
    s_offset: f64,
    /// z of the slope, −R_o cos(π/n) (m).
    plane_z: f64,
    /// Penalty stiffness per node (0 for the thesis contact).
    stiffness: f64,
    /// Contact transient of an impact (s): half a period of a pair's spring under the
    /// effective mass, π √(m_eff / 2k), at most [`defaults::IMPACT_WINDOW`].
    landing: f64,
    /// The wheel's energy scale m g R_o (J): the smallest scale of the energy budget.
    energy_scale: f64,
}

impl Geometry {
    /// The monitor's view of a wheel scene (generic data: any topology).
    pub(super) fn of(scene: &WheelScene, stiffness: f64, gravity: f64) -> Self {
        let n = scene.sides();
        let r_o = scene.outer_radius;
        let half = PI / n as f64;
        Self {
            n,
            r_o,
            rim: scene.rim.clone(),
            axle: scene.axle,
            group: scene.group_of(),
            s_offset: r_o * half.sin(),
            plane_z: scene.plane_z(),
            stiffness,
            energy_scale: scene.mass * gravity * r_o,
            landing: if stiffness > 0.0 {
                let m_eff = contact_effective_mass(scene.mass, scene.i1, r_o, n);
                (PI * (m_eff / (2.0 * stiffness)).sqrt()).min(defaults::IMPACT_WINDOW)
            } else {
                defaults::IMPACT_WINDOW
            },
        }
    }

    fn hub(&self, x: &[Vector3<f64>]) -> Vector3<f64> {
        match self.axle {
            Some([a, b]) => 0.5 * (x[a] + x[b]),
            None => self.rim.iter().map(|&i| x[i]).sum::<Vector3<f64>>() / self.rim.len() as f64,
        }
    }

    /// Spin about the axle, positive rolling downhill (a negative x spin).
    fn omega(&self, x: &[Vector3<f64>], v: &[Vector3<f64>]) -> f64 {
        let (hub, v_hub) = (self.hub(x), self.hub(v));
        let sum: f64 = self
            .rim
            .iter()
            .map(|&i| {
                let r = x[i] - hub;
                let w = v[i] - v_hub;
                (r.y * w.z - r.z * w.y) / (r.y * r.y + r.z * r.z)
            })
            .sum();
        -sum / self.rim.len() as f64
    }

    /// Wheel-frame point → slope coordinates (x, s, h).
    fn slope(&self, p: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(p.x, p.y - self.s_offset, p.z - self.plane_z)
    }
}

/// The contact of one step.
struct StepContact {
    /// Summed contact force per pair (N).
    pair_force: Vec<Vector3<f64>>,
    /// Which pairs carry a force.
    loaded: Vec<bool>,
    /// Summed force (N).
    force: Vector3<f64>,
    /// Smallest normal force of a loaded node (N; +∞ without contact).
    min_normal: f64,
    /// Deepest penetration (m, ≥ 0).
    penetration: f64,
    /// Mean in-plane speed of the loaded nodes (m/s).
    slip_speed: f64,
    /// Whether the contact slides: its load-weighted slip speed Σ f_n |v_t| / Σ f_n over the
    /// loaded nodes exceeds the Stribeck velocity (a node that lands or lifts off carries
    /// almost no load, and its slide under a vanishing Coulomb cap μ f_n is not the wheel's).
    slipping: bool,
    /// Power of the normal damping (W).
    p_damp: f64,
    /// Power of the friction (W).
    p_fric: f64,
    /// s of the most loaded node (NaN without contact).
    pivot: f64,
}

impl StepContact {
    fn of(g: &Geometry, smp: &Sample, x: &[Vector3<f64>], v: &[Vector3<f64>]) -> Self {
        let mut c = StepContact {
            pair_force: vec![Vector3::zeros(); g.n],
            loaded: vec![false; g.n],
            force: Vector3::zeros(),
            min_normal: f64::INFINITY,
            penetration: 0.0,
            slip_speed: 0.0,
            slipping: false,
            p_damp: 0.0,
            p_fric: 0.0,
            pivot: f64::NAN,
        };
        let (mut count, mut strongest) = (0usize, 0.0);
        // Σ f_n |v_t| and Σ f_n over the loaded nodes: the contact's load-weighted slip speed
        let (mut weighted_slip, mut load) = (0.0, 0.0);
        for &(node, f) in smp.contact_forces.iter().flatten() {
            let delta = (g.plane_z - x[node].z).max(0.0);
            let Some(pair) = g.group.get(node).copied().flatten() else {
                continue;
            };
            let vel = v[node];
            c.penetration = c.penetration.max(delta);
            // the ground spring's energy ½kδ² is in E even where the clipped damper
            // cancels the force: its power −kδ v_n belongs to the non-conservative work
            c.p_damp += (f.z - g.stiffness * delta) * vel.z;
            if f == Vector3::zeros() {
                continue;
            }
            c.pair_force[pair] += f;
            c.loaded[pair] = true;
            c.force += f;
            c.min_normal = c.min_normal.min(f.z);
            let speed = vel.xy().norm();
            c.slip_speed += speed;
            weighted_slip += f.z.max(0.0) * speed;
            load += f.z.max(0.0);
            count += 1;
            c.p_fric += f.xy().dot(&vel.xy());
            if f.z > strongest {
                strongest = f.z;
                c.pivot = x[node].y - g.s_offset;
            }
        }
        if count > 0 {
            c.slip_speed /= count as f64;
        }
        c.slipping = load > 0.0 && weighted_slip > defaults::STRIBECK_VELOCITY * load;
        c
    }

    fn airborne(&self) -> bool {
        !self.loaded.iter().any(|&l| l)
    }
}

/// An impact whose contact transient is still running.
struct OpenImpact {
    pair: usize,
    t: f64,
    omega_before: f64,
    impulse: Vector3<f64>,
    /// Pairs loaded just before the touch-down.
    others: Vec<usize>,
    /// Since when the new pair is off the ground again while the old pivot still carries
    /// (None while it is loaded): a graze once that lasts [`defaults::CONTACT_REARM_TIME`].
    left: Option<f64>,
}

/// The previous step.
struct Previous {
    t: f64,
    omega: f64,
    contact: StepContact,
}

/// The streaming monitor of a full rolling run.
pub(super) struct Monitor<'o> {
    g: Geometry,
    output_dt: f64,
    next_output: u64,
    frame_times: Vec<f64>,
    next_frame: usize,
    pub(super) samples: Vec<RollingSample>,
    frames: Vec<WheelFrame>,
    prev: Option<Previous>,
    e0: f64,
    damping_work: f64,
    friction_work: f64,
    residual: f64,
    scale: f64,
    min_normal: f64,
    max_penetration: f64,
    airborne_time: f64,
    slip_time: f64,
    /// Per pair: since when it is off the ground (None while loaded).
    off_since: Vec<Option<f64>>,
    /// The pairs loaded at the last step with a contact (before this one).
    last_loaded: Vec<bool>,
    open: Option<OpenImpact>,
    impacts: Vec<ImpactRecord>,
    /// Who receives the samples and frames, if anyone.
    observer: Option<&'o mut dyn Observer>,
    /// Whether the observer asked to stop.
    stopped: bool,
    /// Whether the frames are kept in the result (not when the observer streams them).
    keep_frames: bool,
}

impl<'o> Monitor<'o> {
    pub(super) fn new(
        g: Geometry,
        output_dt: f64,
        frame_times: &[f64],
        observer: Option<&'o mut dyn Observer>,
    ) -> Self {
        let mut frame_times = frame_times.to_vec();
        frame_times.sort_by(f64::total_cmp);
        // the starting side (pairs 0 and 1) touches; every other pair is off the ground
        let off_since = (0..g.n)
            .map(|k| (k > 1).then_some(f64::NEG_INFINITY))
            .collect();
        let last_loaded = (0..g.n).map(|k| k <= 1).collect();
        let keep_frames = observer.as_deref().is_none_or(|o| o.keeps_frames());
        Self {
            g,
            output_dt,
            next_output: 0,
            frame_times,
            next_frame: 0,
            samples: Vec::new(),
            frames: Vec::new(),
            prev: None,
            e0: 0.0,
            damping_work: 0.0,
            friction_work: 0.0,
            residual: 0.0,
            scale: 0.0,
            min_normal: f64::INFINITY,
            max_penetration: 0.0,
            airborne_time: 0.0,
            slip_time: 0.0,
            off_since,
            last_loaded,
            open: None,
            impacts: Vec::new(),
            observer,
            stopped: false,
            keep_frames,
        }
    }

    /// Whether the observer asked the run to stop.
    pub(super) fn stopped(&self) -> bool {
        self.stopped
    }

    /// Integrates the interval from the previous step to this one.
    /// `integrated`: the contact's work as the integrator integrated it (IMEX's implicit
    /// substeps), which replaces the trapezoidal rule over the step's end points.
    fn integrate(
        &mut self,
        t: f64,
        c: &StepContact,
        energy: (f64, f64),
        integrated: Option<(f64, f64)>,
    ) {
        let (kinetic, total) = energy;
        let Some(p) = &self.prev else {
            self.e0 = total;
            return;
        };
        let dt = t - p.t;
        if let Some((damping, friction)) = integrated {
            self.damping_work = damping;
            self.friction_work = friction;
        } else {
            self.damping_work += 0.5 * dt * (p.contact.p_damp + c.p_damp);
            self.friction_work += 0.5 * dt * (p.contact.p_fric + c.p_fric);
        }
        if c.airborne() {
            self.airborne_time += dt;
        } else if c.slipping {
            self.slip_time += dt;
        }
        if let Some(open) = &mut self.open {
            open.impulse += 0.5 * dt * (p.contact.pair_force[open.pair] + c.pair_force[open.pair]);
        }
        let work = self.damping_work + self.friction_work;
        let change = total - self.e0;
        self.residual = self.residual.max((change - work).abs());
        self.scale = self.scale.max(kinetic).max(change.abs()).max(work.abs());
    }

    /// New contacts and the end of contact transients.
    fn track_impacts(&mut self, t: f64, omega: f64, c: &StepContact) {
        if let Some(open) = &mut self.open {
            let released = open.others.iter().all(|&k| !c.loaded[k]);
            let age = t - open.t;
            let grazed = |left: Option<f64>| {
                left.is_some_and(|left| t - left >= defaults::CONTACT_REARM_TIME)
            };
            if c.loaded[open.pair] && grazed(open.left) {
                // back on the ground after a graze: a new contact (the loop below)
                self.open = None;
            } else if c.loaded[open.pair] {
                // back on the ground (or still there): a lift-off shorter than the re-arm
                // time was chatter of the penalty spring at the touch-down, not a graze
                open.left = None;
                if (released && age >= self.g.landing) || age >= defaults::IMPACT_WINDOW {
                    // the new pair's spring has taken the wheel over
                    self.close_impact(omega);
                }
            } else if released {
                // the new pair bounced off and the old one is gone too
                self.close_impact(omega);
            } else if grazed(Some(*open.left.get_or_insert(t))) {
                // a graze: the new pair stayed off while the old pivot still carried the
                // wheel, so it took nothing over
                self.open = None;
            }
        }
        let before: Vec<usize> = match &self.prev {
            Some(p) => (0..self.g.n).filter(|&k| p.contact.loaded[k]).collect(),
            None => Vec::new(),
        };
        let omega_before = self.prev.as_ref().map_or(omega, |p| p.omega);
        let airborne_before = before.is_empty();
        for k in 0..self.g.n {
            match (c.loaded[k], self.off_since[k]) {
                (true, Some(since)) => {
                    self.off_since[k] = None;
                    // the pair that carried the wheel landing again after a hop shorter than
                    // the impact window: the pivot's chatter, not a new contact group
                    let rearm = if airborne_before && self.last_loaded[k] {
                        defaults::IMPACT_WINDOW
                    } else {
                        defaults::CONTACT_REARM_TIME
                    };
                    if t - since >= rearm {
                        if self.open.as_ref().is_some_and(|o| o.left.is_some()) {
                            // the open one's pair is off while its old pivot carries: a
                            // graze in the making, not an impact
                            self.open = None;
                        }
                        self.close_impact(omega_before);
                        self.open = Some(OpenImpact {
                            pair: k,
                            t,
                            omega_before,
                            impulse: Vector3::zeros(),
                            others: before.iter().copied().filter(|&j| j != k).collect(),
                            left: None,
                        });
                    }
                }
                (false, None) => self.off_since[k] = Some(t),
                _ => {}
            }
        }
        if !c.airborne() {
            self.last_loaded.clone_from(&c.loaded);
        }
    }

    fn close_impact(&mut self, omega_after: f64) {
        if let Some(open) = self.open.take() {
            self.impacts.push(ImpactRecord {
                t: open.t,
                omega_before: open.omega_before,
                omega_after,
                normal_impulse: open.impulse.z,
                tangential_impulse: open.impulse.y,
            });
        }
    }

    /// Keeps the output samples and the requested frames.
    fn record(
        &mut self,
        t: f64,
        (x, v, forces): NodeState<'_>,
        omega: f64,
        c: &StepContact,
        total: f64,
    ) {
        if t >= self.next_output as f64 * self.output_dt - 1e-9 * self.output_dt {
            self.next_output += 1;
            let hub = self.g.slope(&self.g.hub(x));
            let sample = RollingSample {
                t,
                s: hub.y,
                h: hub.z,
                pivot: c.pivot,
                omega,
                normal: c.force.z,
                tangential: c.force.y,
                energy: total - self.e0,
                slip: c.slip_speed,
            };
            self.samples.push(sample);
            if let Some(obs) = self.observer.as_deref_mut() {
                self.stopped |= obs.sample(&sample) == Flow::Stop;
            }
        }
        while self.next_frame < self.frame_times.len()
            && t >= self.frame_times[self.next_frame] - 1e-9
        {
            self.next_frame += 1;
            // slope coordinates are a translation of the model's: velocities carry over
            let frame = WheelFrame {
                t,
                nodes: x.iter().map(|p| self.g.slope(p)).collect(),
                velocities: v.to_vec(),
                member_forces: forces.map(<[f64]>::to_vec).unwrap_or_default(),
            };
            if let Some(obs) = self.observer.as_deref_mut() {
                self.stopped |= obs.frame(&frame) == Flow::Stop;
            }
            if self.keep_frames {
                self.frames.push(frame);
            }
        }
    }

    /// The run's result.
    pub(super) fn finish(mut self, output_dt: f64, wall_time_s: f64) -> FullRun {
        let omega = self.prev.as_ref().map_or(0.0, |p| p.omega);
        self.close_impact(omega);
        let t_total = self.prev.as_ref().map_or(0.0, |p| p.t);
        let validity = self.validity(t_total);
        let impacts = std::mem::take(&mut self.impacts);
        let mut result = summarise(std::mem::take(&mut self.samples), impacts.len(), output_dt);
        result.impact_log = impacts;
        result.validity = validity;
        FullRun {
            result,
            frames: self.frames,
            damping_work: self.damping_work,
            friction_work: self.friction_work,
            wall_time_s,
            settled: None,
        }
    }

    fn validity(&self, t_total: f64) -> RollValidity {
        let fraction = |time: f64| if t_total > 0.0 { time / t_total } else { 0.0 };
        let min_normal = if self.min_normal.is_finite() {
            self.min_normal
        } else {
            0.0
        };
        let energy_balance_error = self.residual / self.scale.max(self.g.energy_scale);
        let tolerance = defaults::PENETRATION_TOLERANCE * self.g.r_o;
        let mut warnings = Vec::new();
        if self.max_penetration > tolerance {
            warnings.push(Warning::SankBelowSlope {
                depth: self.max_penetration,
                tolerance,
                tolerance_fraction: defaults::PENETRATION_TOLERANCE,
            });
        }
        if min_normal < 0.0 {
            warnings.push(Warning::GroundPulled { min_normal });
        }
        if energy_balance_error > defaults::ENERGY_BALANCE_TOLERANCE {
            warnings.push(Warning::EnergyBudget {
                error: energy_balance_error,
                tolerance: defaults::ENERGY_BALANCE_TOLERANCE,
            });
        }
        RollValidity {
            min_normal_force: min_normal,
            airborne_fraction: fraction(self.airborne_time),
            slip_fraction: fraction(self.slip_time),
            max_penetration: self.max_penetration,
            energy_balance_error,
            warnings,
            stopped_at: None,
            convergence: None,
        }
    }
}

/// Node positions and velocities of a step, and its member forces when recorded.
type NodeState<'a> = (&'a [Vector3<f64>], &'a [Vector3<f64>], Option<&'a [f64]>);

impl SampleSink for Monitor<'_> {
    fn accept(&mut self, smp: Sample) -> Result<(), CoreError> {
        if self.stopped {
            return Ok(());
        }
        let (Some(x), Some(v), Some(energy)) = (&smp.nodes, &smp.velocities, smp.energy) else {
            return Ok(());
        };
        let c = StepContact::of(&self.g, &smp, x, v);
        let omega = self.g.omega(x, v);
        self.integrate(smp.t, &c, energy, smp.contact_work);
        self.min_normal = self.min_normal.min(c.min_normal);
        self.max_penetration = self.max_penetration.max(c.penetration);
        self.track_impacts(smp.t, omega, &c);
        self.record(
            smp.t,
            (x, v, smp.member_forces.as_deref()),
            omega,
            &c,
            energy.1,
        );
        self.prev = Some(Previous {
            t: smp.t,
            omega,
            contact: c,
        });
        Ok(())
    }

    fn keep_going(&mut self) -> bool {
        !self.stopped && self.observer.as_deref_mut().is_none_or(|o| o.keep_going())
    }
}
