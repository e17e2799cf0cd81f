//! The hybrid automaton of the rigid wheel: its modes, the smooth step of each, event location
//! and the transitions between modes.
//!
//! Modes: a single contact (pivot or slip, RK4), flight (analytic), a side on the slope (two
//! contacts, ω = 0, sliding with kinetic friction or at rest). Events of a contact mode are the
//! sign changes over a step of θ − π/n and θ + π/n (a neighbour touches), N (lift-off),
//! μ_s N − |F_t| (stick → slip) and the slip velocity (slip → stick); each is located by
//! bisection on the step length of the RK4 step from the step's start, to round-off. A flight
//! event is the first root of a vertex gap h(τ) − R cos ψ_j(τ), bracketed by sign changes of
//! the gap and of its rate (a grazing minimum) and bisected on the exact flight solution.

use super::wheel::{Body, ContactState, Wheel};
use crate::validity::ImpactRecord;
use tensegrity_core::Warning;

/// Gap below which a vertex counts as touching, as a fraction of R.
pub(crate) const GAP_TOL: f64 = 1e-10;
/// Normal velocity below which a touching vertex stays in contact, as a fraction of √(g R).
const VEL_TOL: f64 = 1e-9;
/// Approach speed below which an impact is taken as plastic (ends Zeno-like bouncing), as a
/// fraction of √(g R).
const ZENO_TOL: f64 = 1e-6;
/// Sweeps of sequential impulses over the touching vertices at one impact.
const MAX_SWEEPS: usize = 100;
/// Largest number of events of a run.
pub(crate) const MAX_EVENTS: usize = 2_000_000;
/// Largest number of consecutive events that advance the time by less than 10⁻⁹ dt.
const MAX_STALLED: usize = 10_000;

/// The current mode and its state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mode {
    /// One contact vertex k, pivoting (`sigma` None) or slipping with F_t = σ N.
    Contact {
        /// Contact vertex.
        k: usize,
        /// σ of the slip, None when pivoting.
        sigma: Option<f64>,
        /// θ, θ̇, s_c, w, friction work.
        y: ContactState,
    },
    /// No contact; `last` is the last contact's position along the slope.
    Flight {
        /// The state.
        b: Body,
        /// Last contact position (m).
        last: f64,
    },
    /// Vertices k (downhill) and k − 1 on the slope, ω = 0, sliding with acceleration `accel`.
    Side {
        /// Downhill vertex.
        k: usize,
        /// The state.
        b: Body,
        /// s̈ (m/s²).
        accel: f64,
    },
    /// At rest on the side (k, k − 1).
    Rest {
        /// Downhill vertex.
        k: usize,
        /// The state.
        b: Body,
    },
}

/// The running simulation and its bookkeeping.
#[derive(Debug, Clone)]
pub(crate) struct Hybrid {
    /// The wheel.
    pub w: Wheel,
    /// Current mode.
    pub mode: Mode,
    /// Current time (s).
    pub t: f64,
    /// Friction work of the finished slip phases and side slides (J).
    pub friction_work: f64,
    /// Energy dissipated by normal impulses (J).
    pub impact_loss: f64,
    /// Energy dissipated by tangential impulses (J).
    pub impulse_friction_loss: f64,
    /// The impacts.
    pub impacts: Vec<ImpactRecord>,
    /// Time in flight (s).
    pub flight_time: f64,
    /// Time slipping (s).
    pub slip_time: f64,
    /// Smallest normal force seen in a contact mode (N).
    pub min_normal: f64,
    /// Events so far.
    pub events: usize,
    /// Consecutive events without progress.
    pub stalled: usize,
    /// Impacts taken as plastic because their approach speed was below the Zeno tolerance.
    pub zeno_truncations: usize,
    /// Impacts whose restitution was lowered so as not to create energy.
    pub restitution_lowered: usize,
    /// Problems met.
    pub warnings: Vec<Warning>,
}

/// Bisection of a predicate false at `lo` and true at `hi`, to round-off.
pub(crate) fn bisect(mut lo: f64, mut hi: f64, f: impl Fn(f64) -> bool) -> (f64, f64) {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    (lo, hi)
}

impl Hybrid {
    /// At rest on the side of vertices 0 (downhill, at s = 0) and n − 1.
    pub fn start(w: Wheel) -> Self {
        let b = Body {
            s: -w.r * w.half.sin(),
            h: w.r * w.half.cos(),
            alpha: -w.half,
            u: 0.0,
            v: 0.0,
            omega: 0.0,
        };
        let mut sim = Self {
            w,
            mode: Mode::Rest { k: 0, b },
            t: 0.0,
            friction_work: 0.0,
            impact_loss: 0.0,
            impulse_friction_loss: 0.0,
            impacts: Vec::new(),
            flight_time: 0.0,
            slip_time: 0.0,
            min_normal: w.m * w.gn,
            events: 0,
            stalled: 0,
            zeno_truncations: 0,
            restitution_lowered: 0,
            warnings: Vec::new(),
        };
        sim.mode = sim.on_side(b, 0, w.n - 1);
        sim
    }

    fn vel_tol(&self) -> f64 {
        VEL_TOL * (self.w.gn.hypot(self.w.gs) * self.w.r).sqrt()
    }

    /// The body of the current mode.
    pub fn body(&self) -> Body {
        match self.mode {
            Mode::Contact { k, y, .. } => self.w.body_of(&y, k),
            Mode::Flight { b, .. } | Mode::Side { b, .. } | Mode::Rest { b, .. } => b,
        }
    }

    /// Total friction work so far (J).
    pub fn work(&self) -> f64 {
        match self.mode {
            Mode::Contact { y, .. } => y[4],
            _ => self.friction_work,
        }
    }

    /// Advances to `t_out` with steps of at most `dt`; false when the run had to stop.
    pub fn advance_to(&mut self, t_out: f64, dt: f64) -> bool {
        while self.t < t_out {
            if self.events >= MAX_EVENTS || self.stalled >= MAX_STALLED {
                let why = if self.stalled >= MAX_STALLED {
                    format!(
                        "{MAX_STALLED} events without the time advancing by 1e-9 dt (chattering)"
                    )
                } else {
                    format!("the event count reached its cap of {MAX_EVENTS}")
                };
                self.warnings.push(Warning::RigidStopped {
                    t: self.t,
                    reason: why,
                });
                return false;
            }
            let h = dt.min(t_out - self.t);
            let (tau, event) = self.step(h);
            if event {
                self.events += 1;
                self.stalled = if tau > 1e-9 * dt { 0 } else { self.stalled + 1 };
            }
            self.t = if tau >= h && h == t_out - self.t {
                t_out
            } else {
                self.t + tau
            };
        }
        true
    }

    /// One step of at most `h`: the time advanced and whether it ended at an event.
    fn step(&mut self, h: f64) -> (f64, bool) {
        match self.mode {
            Mode::Contact { k, sigma, y } => self.contact_step(k, sigma, y, h),
            Mode::Flight { b, last } => self.flight_step(b, last, h),
            Mode::Side { k, b, accel } => self.side_step(k, b, accel, h),
            Mode::Rest { .. } => (h, false),
        }
    }

    /// [θ > π/n, θ < −π/n, N < 0, friction event] of a contact state.
    fn predicates(&self, y: &ContactState, sigma: Option<f64>) -> [bool; 4] {
        let f = self.w.forces(y[0], y[1], sigma);
        let friction = match sigma {
            None => f.tangential.abs() > self.w.mu_s * f.normal,
            Some(sg) => sg * y[3] > 0.0,
        };
        [
            y[0] > self.w.half,
            y[0] < -self.w.half,
            f.normal < 0.0,
            friction,
        ]
    }

    fn contact_step(
        &mut self,
        k: usize,
        sigma: Option<f64>,
        y: ContactState,
        h: f64,
    ) -> (f64, bool) {
        let w = self.w;
        let y1 = w.rk4(&y, sigma, h);
        let (p0, p1) = (self.predicates(&y, sigma), self.predicates(&y1, sigma));
        let mut first: Option<(f64, f64, usize)> = None;
        for i in (0..4).filter(|&i| !p0[i] && p1[i]) {
            let (lo, hi) = bisect(0.0, h, |tau| {
                self.predicates(&w.rk4(&y, sigma, tau), sigma)[i]
            });
            if first.is_none_or(|(_, best, _)| hi < best) {
                first = Some((lo, hi, i));
            }
        }
        let (tau, end) = match first {
            None => (h, y1),
            Some((lo, _, _)) => (lo, w.rk4(&y, sigma, lo)),
        };
        let normal = w.forces(end[0], end[1], sigma).normal;
        self.min_normal = self.min_normal.min(normal);
        if sigma.is_some() {
            self.slip_time += tau;
        }
        match first {
            None => {
                self.mode = Mode::Contact { k, sigma, y: y1 };
                (h, false)
            }
            Some((_, _, i)) => {
                self.on_contact_event(k, sigma, end, i, self.t + tau);
                (tau, true)
            }
        }
    }

    fn on_contact_event(
        &mut self,
        k: usize,
        sigma: Option<f64>,
        mut y: ContactState,
        i: usize,
        at: f64,
    ) {
        let n = self.w.n;
        let b = self.w.body_of(&y, k);
        match (i, sigma) {
            (0, _) => self.impact(b, (k + 1) % n, y[4], at),
            (1, _) => self.impact(b, (k + n - 1) % n, y[4], at),
            (2, _) => self.mode = self.flight(y, k),
            (_, None) => {
                let f = self.w.forces(y[0], y[1], None);
                let sg = self.w.mu_k * f.tangential.signum();
                self.mode = if self.w.forces(y[0], y[1], Some(sg)).normal < 0.0 {
                    self.flight(y, k)
                } else {
                    Mode::Contact {
                        k,
                        sigma: Some(sg),
                        y,
                    }
                };
            }
            (_, Some(_)) => {
                y[3] = 0.0;
                self.mode = self.single(y, k);
            }
        }
    }

    /// Flight from a contact state (its friction work is banked).
    fn flight(&mut self, y: ContactState, k: usize) -> Mode {
        self.friction_work = y[4];
        Mode::Flight {
            b: self.w.body_of(&y, k),
            last: y[2],
        }
    }

    /// The single-contact mode on vertex k from a contact state whose vertex does not
    /// approach the slope: slip if it slides, else pivot when N ≥ 0 and |F_t| ≤ μ_s N, slip
    /// against the needed friction when N ≥ 0 only, flight when the contact would pull.
    fn single(&mut self, mut y: ContactState, k: usize) -> Mode {
        let w = self.w;
        let contact = |sigma| Mode::Contact { k, sigma, y };
        if y[3].abs() > self.vel_tol() {
            let sg = -w.mu_k * y[3].signum();
            if w.forces(y[0], y[1], Some(sg)).normal < 0.0 {
                return self.flight(y, k);
            }
            return contact(Some(sg));
        }
        y[3] = 0.0;
        let f = w.forces(y[0], y[1], None);
        if f.normal < 0.0 {
            return self.flight(y, k);
        }
        if f.tangential.abs() <= w.mu_s * f.normal {
            return Mode::Contact { k, sigma: None, y };
        }
        let sg = w.mu_k * f.tangential.signum();
        if w.forces(y[0], y[1], Some(sg)).normal < 0.0 {
            return self.flight(y, k);
        }
        Mode::Contact {
            k,
            sigma: Some(sg),
            y,
        }
    }

    /// The mode of a body whose touching vertices do not approach the slope.
    fn decide(&mut self, b: Body, last: f64) -> Mode {
        let (w, vtol) = (self.w, self.vel_tol());
        let mut touching: Vec<usize> = (0..w.n)
            .filter(|&j| w.gap(&b, j) <= GAP_TOL * w.r && w.vertex_velocity(&b, j).1 <= vtol)
            .collect();
        touching.sort_by(|&a, &c| w.vertex_s(&b, c).total_cmp(&w.vertex_s(&b, a)));
        match touching.as_slice() {
            [] => Mode::Flight { b, last },
            [k] => {
                let y = w.contact_of(&b, *k, self.friction_work);
                self.single(y, *k)
            }
            [kd, .., ku] => self.on_side(b, *kd, *ku),
        }
    }

    /// Two touching vertices with zero normal velocity (a side on the slope, so ω = v = 0):
    /// pivot or slip about the downhill vertex when that lifts the other, or about the uphill
    /// one likewise, else slide on the side with kinetic friction, else rest.
    fn on_side(&mut self, b: Body, kd: usize, ku: usize) -> Mode {
        let w = self.w;
        for (k, sign) in [(kd, 1.0), (ku, -1.0)] {
            let y = w.contact_of(&b, k, self.friction_work);
            if let Mode::Contact { sigma, y, .. } = self.single(y, k) {
                if sign * w.forces(y[0], y[1], sigma).theta_dd >= 0.0 {
                    return Mode::Contact { k, sigma, y };
                }
            }
        }
        let flat = Body {
            h: w.r * w.half.cos(),
            alpha: b.alpha - w.half - w.psi(&b, kd),
            v: 0.0,
            omega: 0.0,
            ..b
        };
        if b.u.abs() > self.vel_tol() {
            let accel = w.gs - w.mu_k * w.gn * b.u.signum();
            return Mode::Side {
                k: kd,
                b: flat,
                accel,
            };
        }
        let flat = Body { u: 0.0, ..flat };
        if w.gs <= w.mu_s * w.gn {
            Mode::Rest { k: kd, b: flat }
        } else {
            Mode::Side {
                k: kd,
                b: flat,
                accel: w.gs - w.mu_k * w.gn,
            }
        }
    }

    fn side_step(&mut self, k: usize, b: Body, accel: f64, h: f64) -> (f64, bool) {
        let stop = if b.u * accel < 0.0 {
            Some(-b.u / accel)
        } else {
            None
        };
        let tau = stop.map_or(h, |s| s.min(h));
        let mut end = Body {
            s: b.s + b.u * tau + 0.5 * accel * tau * tau,
            u: b.u + accel * tau,
            ..b
        };
        self.friction_work += self.w.mu_k * self.w.m * self.w.gn * (end.s - b.s).abs();
        self.slip_time += tau;
        match stop {
            Some(s) if s <= h => {
                end.u = 0.0;
                let ku = (k + self.w.n - 1) % self.w.n;
                self.mode = self.on_side(end, k, ku);
                (tau, true)
            }
            _ => {
                self.mode = Mode::Side { k, b: end, accel };
                (h, false)
            }
        }
    }

    fn flight_step(&mut self, b: Body, last: f64, h: f64) -> (f64, bool) {
        let w = self.w;
        let mut first: Option<(f64, usize)> = None;
        for j in 0..w.n {
            if let Some(tau) = self.touchdown(&b, j, h) {
                if first.is_none_or(|(best, _)| tau < best) {
                    first = Some((tau, j));
                }
            }
        }
        match first {
            None => {
                self.flight_time += h;
                self.mode = Mode::Flight {
                    b: w.fly(&b, h),
                    last,
                };
                (h, false)
            }
            Some((tau, j)) => {
                self.flight_time += tau;
                self.impact(w.fly(&b, tau), j, self.friction_work, self.t + tau);
                (tau, true)
            }
        }
    }

    /// The first time in (0, h] at which vertex j reaches the slope in flight, if any.
    fn touchdown(&self, b: &Body, j: usize, h: f64) -> Option<f64> {
        let w = self.w;
        let gap = |tau| w.gap(&w.fly(b, tau), j);
        let rate = |tau| w.gap_rate(&w.fly(b, tau), j);
        let (g0, r0, tol) = (gap(0.0), rate(0.0), GAP_TOL * w.r);
        let mut a = 0.0;
        if g0 <= tol {
            if g0 < -tol || r0 < -self.vel_tol() {
                return Some(0.0);
            }
            if r0 <= self.vel_tol() || rate(h) >= 0.0 {
                return None; // lifting off, or still rising
            }
            a = bisect(0.0, h, |tau| rate(tau) < 0.0).0;
        }
        if gap(h) <= 0.0 {
            return Some(bisect(a, h, |tau| gap(tau) <= 0.0).0);
        }
        if rate(a) < 0.0 && rate(h) > 0.0 {
            let low = bisect(a, h, |tau| rate(tau) >= 0.0).1;
            if gap(low) <= 0.0 {
                return Some(bisect(a, low, |tau| gap(tau) <= 0.0).0);
            }
        }
        None
    }

    /// An impact of vertex `new`: the impact law there, then plastic impulses at whichever
    /// touching vertex still approaches the slope until none does; then the next mode.
    fn impact(&mut self, mut b: Body, new: usize, work: f64, at: f64) {
        let (w, vtol) = (self.w, self.vel_tol());
        self.friction_work = work;
        let omega_before = b.omega;
        let kinetic_before = w.energies(&b).0;
        let approach = -w.vertex_velocity(&b, new).1;
        let e = if approach < ZENO_TOL * (w.gn.hypot(w.gs) * w.r).sqrt() {
            self.zeno_truncations += usize::from(w.e > 0.0);
            0.0
        } else {
            w.e
        };
        let (mut total, used) = w.dissipative_impulse(&mut b, new, e);
        self.restitution_lowered += usize::from(used < e);
        let contacts: Vec<usize> = (0..w.n)
            .filter(|&j| j == new || w.gap(&b, j) <= GAP_TOL * w.r)
            .collect();
        let mut converged = false;
        for _ in 0..MAX_SWEEPS {
            let worst = contacts
                .iter()
                .map(|&j| (w.vertex_velocity(&b, j).1, j))
                .min_by(|x, y| x.0.total_cmp(&y.0));
            match worst {
                Some((cn, j)) if cn < -vtol => {
                    let p = w.impulse(&mut b, j, 0.0);
                    total.normal += p.normal;
                    total.tangential += p.tangential;
                    total.normal_loss += p.normal_loss;
                    total.friction_loss += p.friction_loss;
                }
                _ => {
                    converged = true;
                    break;
                }
            }
        }
        if !converged {
            self.warnings.push(Warning::ImpactNotConverged {
                t: at,
                sweeps: MAX_SWEEPS,
            });
        }
        let dissipated = total.normal_loss + total.friction_loss;
        if dissipated < -1e-9 * kinetic_before {
            self.warnings.push(Warning::ImpactCreatedEnergy {
                t: at,
                energy: -dissipated,
            });
        }
        self.impact_loss += total.normal_loss;
        self.impulse_friction_loss += total.friction_loss;
        self.impacts.push(ImpactRecord {
            t: at,
            omega_before,
            omega_after: b.omega,
            normal_impulse: total.normal,
            tangential_impulse: total.tangential,
        });
        let last = w.vertex_s(&b, new);
        self.mode = self.decide(b, last);
    }
}
