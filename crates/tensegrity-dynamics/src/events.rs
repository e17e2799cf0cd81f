//! Events: scalar functions g(t, y) of the state whose sign changes the driver locates.
//!
//! After every accepted step [t₀, t₁] each event function is evaluated at t₁; where
//! g(t₀) ≠ 0 and sign g(t₀) ≠ sign g(t₁), the crossing is located by bisection on the
//! integrator's dense output (4th order for [`Dopri5`](super::Dopri5)) down to
//! |b − a| ≤ 10⁻¹³ max(|b|, 1), and reported as an [`EventHit`] at the right end b of the
//! final bracket (the first time at which the new sign holds). Integrators without dense
//! output get the linear interpolant of the step's end states (2nd-order event times; put
//! output times or smaller steps around an event that matters). A terminal event stops the
//! run at the earliest terminal crossing of the step, with the state interpolated there.

use super::integrator::Integrator;
use super::model::{vec3, Model, NodeRef};
use nalgebra::Vector3;
use std::fmt;

/// Read-only view of a state in file numbering, passed to event functions.
#[derive(Debug, Clone, Copy)]
pub struct StateView<'a> {
    model: &'a Model,
    y: &'a [f64],
}

impl<'a> StateView<'a> {
    /// A view of the class-1 state `y` of `model`.
    pub fn new(model: &'a Model, y: &'a [f64]) -> Self {
        Self { model, y }
    }

    /// Position of file node `i`.
    pub fn node(&self, i: usize) -> Vector3<f64> {
        match self.model.node_map[i] {
            NodeRef::Free(c) => vec3(self.y, c),
            NodeRef::Anchor(p) => p,
        }
    }

    /// Velocity of file node `i`.
    pub fn velocity(&self, i: usize) -> Vector3<f64> {
        match self.model.node_map[i] {
            NodeRef::Free(c) => vec3(&self.y[3 * self.model.n1..], c),
            NodeRef::Anchor(_) => Vector3::zeros(),
        }
    }

    /// Number of file nodes.
    pub fn n_nodes(&self) -> usize {
        self.model.n_nodes
    }
}

/// An event function g(t, state); an event happens where g changes sign.
pub type EventFn = Box<dyn Fn(f64, &StateView<'_>) -> f64 + Send + Sync>;

/// An event to locate.
pub struct Event {
    /// Name reported in [`EventHit`].
    pub name: String,
    /// The event function.
    pub function: EventFn,
    /// Stop the run at the first occurrence.
    pub terminal: bool,
}

impl fmt::Debug for Event {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Event")
            .field("name", &self.name)
            .field("terminal", &self.terminal)
            .finish()
    }
}

/// A located event.
#[derive(Debug, Clone, PartialEq)]
pub struct EventHit {
    /// The event's name.
    pub name: String,
    /// When it happened (s), to ~1e-12 relative with dense output.
    pub t: f64,
}

/// Sign-change detection and root location for the events of one run.
pub(crate) struct EventTracker<'a> {
    events: &'a [Event],
    g_prev: Vec<f64>,
    /// The state at the start of the step (kept only for the linear interpolant).
    y_prev: Vec<f64>,
    linear: bool,
    buf: Vec<f64>,
    /// The crossings found so far.
    pub hits: Vec<EventHit>,
}

impl<'a> EventTracker<'a> {
    /// Evaluates the events at the initial state.
    pub fn new(events: &'a [Event], model: &Model, t0: f64, y0: &[f64], dense: bool) -> Self {
        let g_prev = events
            .iter()
            .map(|e| (e.function)(t0, &StateView::new(model, y0)))
            .collect();
        let linear = !dense && !events.is_empty();
        Self {
            events,
            g_prev,
            y_prev: if linear { y0.to_vec() } else { Vec::new() },
            linear,
            buf: vec![0.0; y0.len()],
            hits: Vec::new(),
        }
    }

    /// Remembers the state at the start of a step (for the linear interpolant).
    pub fn before_step(&mut self, y: &[f64]) {
        if self.linear {
            self.y_prev.copy_from_slice(y);
        }
    }

    /// The state at `t` inside the step [t0, t1] that ended in `y1`, into `out`.
    pub fn state_at(
        &self,
        integ: &dyn Integrator<Model>,
        (t0, t1): (f64, f64),
        y1: &[f64],
        t: f64,
        out: &mut [f64],
    ) {
        if !integ.interpolate(t, out) {
            let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 1.0 };
            for ((o, a), b) in out.iter_mut().zip(&self.y_prev).zip(y1) {
                *o = a + w * (b - a);
            }
        }
    }

    /// Checks every event over the accepted step [t0, t1] ending in `y1`, records the
    /// crossings and returns the earliest terminal one.
    pub fn after_step(
        &mut self,
        model: &Model,
        integ: &dyn Integrator<Model>,
        (t0, t1): (f64, f64),
        y1: &[f64],
    ) -> Option<f64> {
        let mut stop_at: Option<f64> = None;
        for ei in 0..self.events.len() {
            let ev = &self.events[ei];
            let g1 = (ev.function)(t1, &StateView::new(model, y1));
            let g0 = self.g_prev[ei];
            if g0 != 0.0 && (g0 < 0.0) != (g1 < 0.0) {
                let tc = self.locate(model, integ, ev, (t0, t1), y1, g0);
                self.hits.push(EventHit {
                    name: ev.name.clone(),
                    t: tc,
                });
                if ev.terminal {
                    stop_at = Some(stop_at.map_or(tc, |s| s.min(tc)));
                }
            }
            self.g_prev[ei] = g1;
        }
        stop_at
    }

    /// Bisection for the sign change of `ev` in [t0, t1] (g(t0) = g0).
    fn locate(
        &mut self,
        model: &Model,
        integ: &dyn Integrator<Model>,
        ev: &Event,
        (t0, t1): (f64, f64),
        y1: &[f64],
        g0: f64,
    ) -> f64 {
        let (mut a, mut b) = (t0, t1);
        let mut ga = g0;
        let mut buf = std::mem::take(&mut self.buf);
        for _ in 0..200 {
            if b - a <= 1e-13 * b.abs().max(1.0) {
                break;
            }
            let m = 0.5 * (a + b);
            self.state_at(integ, (t0, t1), y1, m, &mut buf);
            let gm = (ev.function)(m, &StateView::new(model, &buf));
            if (gm < 0.0) == (ga < 0.0) && gm != 0.0 {
                a = m;
                ga = gm;
            } else {
                b = m;
            }
        }
        self.buf = buf;
        b
    }
}
