//! Animations of a structure over time (`--animate FILE.gif` or `FILE.webm` of `simulate`
//! and `roll`): the members drawn with [`crate::draw`] (to scale, bars and strings as the
//! drawings draw them), the ground as a grey line and the time in the title, one frame per
//! wanted time, written by the io crate's [`AnimationSink`] (at its size and dpi, the frames
//! drawn in parallel): an animated GIF in one palette, or an AV1 video in WebM.
//!
//! Frames: N = round(fps · duration) ≥ 2 frames ([`AnimationSpec`]) at the simulated times
//! t_k = k·t_end/(N − 1), k = 0 … N − 1, shown 1/fps s each, so the whole run plays in
//! `duration` seconds. The run hands the animation its node positions as it goes
//! ([`NodeFrames`]); the animation keeps only the N frames it draws (N × nodes × 24 bytes,
//! never the trajectory) and draws them when the run ends, once the camera is known:
//! [`Camera::Fixed`] frames the union of every frame (a structure that drops or moves about),
//! [`Camera::Follow`] a window of fixed size centred on each frame (a wheel rolling away).
//! A sample that passes several wanted times stands for each of them, so a run that ends
//! normally has exactly N frames.
//!
//! The view is a [`View`]; in the side view (y, z) the picture may be turned by `tilt` about
//! ι̂₁ (the rolling runs' slope coordinates turned by −incline show the slope going down).

use crate::draw::{self, Group, View};
use crate::error::Result;
use nalgebra::{Rotation3, Vector3};
use tensegrity_core::request::InvalidParameter;
use tensegrity_io::figure::{Figure, Note, Series};
use tensegrity_io::sink::{AnimationSink, NodeFrames};

/// Frames per second unless told.
pub const DEFAULT_FPS: f64 = 10.0;
/// Playing time unless told (s).
pub const DEFAULT_DURATION_S: f64 = 5.0;
/// The most frames an animation may have.
pub const MAX_FRAMES: usize = 2000;

/// The frame rate and the playing time of an animation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnimationSpec {
    /// Frames per second of the GIF (0 < fps ≤ 50).
    pub fps: f64,
    /// Playing time (s).
    pub duration: f64,
}

impl Default for AnimationSpec {
    fn default() -> Self {
        Self {
            fps: DEFAULT_FPS,
            duration: DEFAULT_DURATION_S,
        }
    }
}

impl AnimationSpec {
    /// The spec, checked: `fps` in (0, 50], N = round(fps · duration) in [2, [`MAX_FRAMES`]].
    pub fn new(fps: Option<f64>, duration: Option<f64>) -> Result<Self, InvalidParameter> {
        let spec = Self {
            fps: fps.unwrap_or(DEFAULT_FPS),
            duration: duration.unwrap_or(DEFAULT_DURATION_S),
        };
        if !(spec.fps > 0.0 && spec.fps <= 50.0) {
            return Err(InvalidParameter::new(
                "fps",
                spec.fps,
                "frames per second must lie in (0, 50]",
            ));
        }
        let n = spec.fps * spec.duration;
        if !(n.is_finite() && n.round() >= 2.0 && n.round() <= MAX_FRAMES as f64) {
            return Err(InvalidParameter::new(
                "duration",
                spec.duration,
                format!("`fps` × `duration` must give 2 to {MAX_FRAMES} frames (it gives {n:.1})"),
            ));
        }
        Ok(spec)
    }

    /// The number of frames, round(fps · duration).
    pub fn frames(&self) -> usize {
        (self.fps * self.duration).round() as usize
    }

    /// The simulated times of the frames over [0, `t_end`].
    pub fn times(&self, t_end: f64) -> Vec<f64> {
        let n = self.frames().max(2);
        (0..n).map(|k| t_end * k as f64 / (n - 1) as f64).collect()
    }
}

/// How the picture follows the structure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Camera {
    /// One window holding every frame (and the ground's point).
    Fixed,
    /// A window of fixed size centred on each frame's structure.
    Follow,
}

/// What is drawn besides the moving nodes: members, ground, view.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenery {
    /// Title before the time stamp.
    pub title: String,
    /// Bar end nodes.
    pub bars: Vec<[usize; 2]>,
    /// String end nodes.
    pub strings: Vec<[usize; 2]>,
    /// The ground plane (a point, its normal), if there is one.
    pub ground: Option<(Vector3<f64>, Vector3<f64>)>,
    /// The projection.
    pub view: View,
    /// Turn of the side view about ι̂₁ (rad).
    pub tilt: f64,
    /// Seen along ι̂₂ instead of ι̂₁ (the side view then shows (x, z)).
    pub along_y: bool,
    /// The camera.
    pub camera: Camera,
}

impl Scenery {
    /// The members of `structure` in the side view with a fixed camera, seen along the
    /// horizontal axis in which the structure is the thinner (x or y), on `ground` if any.
    pub fn structure(
        title: impl Into<String>,
        structure: &tensegrity_core::Structure,
        ground: Option<&tensegrity_dynamics::Ground>,
    ) -> Self {
        let (mut lo, mut hi) = (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN));
        for p in structure.nodes() {
            (lo, hi) = (lo.inf(p), hi.sup(p));
        }
        let extent = hi - lo;
        Self {
            title: title.into(),
            bars: structure.bars().iter().map(|b| b.nodes).collect(),
            // a clustered string is drawn as strings, segment by segment
            strings: (structure.strings().iter().map(|s| s.nodes))
                .chain(structure.clusters().iter().flat_map(|c| c.segments()))
                .collect(),
            ground: ground.map(|g| (g.point, g.normal)),
            view: View::Side,
            tilt: 0.0,
            along_y: extent.x > extent.y,
            camera: Camera::Fixed,
        }
    }
}

/// An animation being recorded: a [`NodeFrames`] for the run's outputs.
#[derive(Debug)]
pub struct Animation {
    sink: AnimationSink,
    scenery: Scenery,
    times: Vec<f64>,
    tolerance: f64,
    next: usize,
    kept: Vec<(f64, Vec<Vector3<f64>>)>,
    invalid: Option<String>,
}

impl Animation {
    /// An animation into `sink` (opened before the run) of the frames at `spec.times(t_end)`;
    /// a node sample counts for a wanted time from `tolerance` (s) before it.
    pub fn new(sink: AnimationSink, scenery: Scenery, spec: &AnimationSpec, t_end: f64) -> Self {
        let times = spec.times(t_end);
        let tolerance = 1e-9 * t_end.abs().max(1e-300);
        Self {
            sink,
            scenery,
            times,
            tolerance,
            next: 0,
            kept: Vec::new(),
            invalid: None,
        }
    }

    /// The same with another tolerance (s), e.g. a fixed step.
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance.max(self.tolerance);
        self
    }

    /// The wanted times (s), for a run that samples at given times.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Frames kept so far.
    pub fn kept(&self) -> usize {
        self.kept.len()
    }

    /// Marks every frame as showing a run that is not valid, `reason`
    /// ([`tensegrity_io::figure::Figure::mark_invalid`]); the run's validity is known at its
    /// end, before [`Animation::finish`] draws the frames.
    pub fn mark_invalid(&mut self, reason: impl Into<String>) {
        self.invalid = Some(reason.into());
    }

    /// The same animation marked when `valid` is false, the reason from `warnings`
    /// ([`crate::warning::invalid_reason`]).
    pub fn marked(mut self, valid: bool, warnings: &[tensegrity_core::Warning]) -> Self {
        if !valid {
            self.mark_invalid(crate::warning::invalid_reason(warnings));
        }
        self
    }

    /// Draws the frames kept and writes the file; the number of frames.
    pub fn finish(self) -> Result<usize> {
        let Self {
            mut sink,
            scenery,
            kept,
            invalid,
            ..
        } = self;
        let turned: Vec<(f64, Vec<(f64, f64)>)> = kept
            .iter()
            .map(|(t, nodes)| (*t, scenery.projected(nodes)))
            .collect();
        let windows = scenery.windows(&turned);
        // one size for every frame: the first's (the windows' aspects agree to round-off)
        let mut size = None;
        let figures: Vec<_> = kept
            .iter()
            .zip(windows)
            .map(|((t, nodes), window)| {
                let mut figure = scenery.frame(*t, nodes, window);
                figure.invalid.clone_from(&invalid);
                let (w, h) = *size.get_or_insert(figure.panel_size);
                figure.with_panel_size(w, h)
            })
            .collect();
        // drawn in parallel, one palette
        sink.frames_of(&figures)?;
        Ok(sink.finish()?)
    }
}

impl NodeFrames for Animation {
    fn frame(&mut self, t: f64, nodes: &[Vector3<f64>]) -> tensegrity_io::Result<()> {
        while self.next < self.times.len() && t >= self.times[self.next] - self.tolerance {
            self.kept.push((t, nodes.to_vec()));
            self.next += 1;
        }
        Ok(())
    }
}

/// A window (x0, x1, y0, y1) of the picture plane.
type Window = (f64, f64, f64, f64);

impl Scenery {
    /// The rotation of the tilt (about ι̂₁), after ι̂₁ turned onto ι̂₂ when seen along ι̂₂.
    fn turn(&self) -> Rotation3<f64> {
        let yaw = if self.along_y {
            std::f64::consts::FRAC_PI_2
        } else {
            0.0
        };
        Rotation3::from_axis_angle(&Vector3::x_axis(), self.tilt)
            * Rotation3::from_axis_angle(&Vector3::z_axis(), yaw)
    }

    fn projected(&self, nodes: &[Vector3<f64>]) -> Vec<(f64, f64)> {
        let r = self.turn();
        nodes.iter().map(|p| self.view.project(&(r * p))).collect()
    }

    /// The window of each frame.
    fn windows(&self, frames: &[(f64, Vec<(f64, f64)>)]) -> Vec<Window> {
        let boxes: Vec<Window> = frames.iter().map(|(_, p)| bounds(p)).collect();
        match self.camera {
            Camera::Fixed => {
                let mut all = boxes
                    .iter()
                    .fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |a, b| {
                        (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3))
                    });
                if let Some((p, _)) = self.ground {
                    let (_, v) = self.view.project(&(self.turn() * p));
                    (all.2, all.3) = (all.2.min(v), all.3.max(v));
                }
                vec![padded(all, 0.08); frames.len()]
            }
            Camera::Follow => {
                let w = boxes.iter().map(|b| b.1 - b.0).fold(0.0, f64::max);
                let h = boxes.iter().map(|b| b.3 - b.2).fold(0.0, f64::max);
                let side = 1.4 * w.max(h).max(1e-9);
                boxes
                    .iter()
                    .map(|b| {
                        let (cx, cy) = (0.5 * (b.0 + b.1), 0.5 * (b.2 + b.3));
                        let (hw, hh) = (0.5 * side, 0.5 * side);
                        (cx - hw, cx + hw, cy - hh, cy + hh)
                    })
                    .collect()
            }
        }
    }

    /// One frame: the window's outline in white (it fixes the axes), the ground clipped to
    /// the window, the members.
    fn frame(&self, t: f64, nodes: &[Vector3<f64>], (x0, x1, y0, y1): Window) -> Figure {
        let r = self.turn();
        let turned: Vec<Vector3<f64>> = nodes.iter().map(|p| r * p).collect();
        // bars last: on top of the strings
        let groups = [
            Group::new("strings", draw::RED, self.strings.clone()),
            Group::new("bars", draw::BLUE, self.bars.clone()),
        ];
        let title = format!("{}   t = {t:.3} s", self.title);
        let members = draw::structure_panel(title, self.view, &turned, &groups);
        let frame = Series::new("", vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)])
            .with_color((255, 255, 255));
        let mut panel = members.clone().legend_above(0.4);
        panel.series = vec![frame];
        if self.tilt != 0.0 && self.view == View::Side {
            // turned: the axes are the page's, not the structure's
            (panel.x_label, panel.y_label) = ("horizontal [m]".into(), "vertical [m]".into());
        } else if self.along_y && self.view == View::Side {
            panel.x_label = "ι₁ [m]".into();
        }
        if let Some(segment) = self.ground_segment(&r, (x0, x1, y0, y1)) {
            panel
                .series
                .push(Series::new("ground", segment).with_color(draw::GREY));
        } else if let Some(gap) = self.ground_gap(nodes) {
            // the ground left the window (a wheel in flight, followed by the camera): say
            // where it is, so the frame does not show a structure floating over nothing
            let at = (x0 + 0.04 * (x1 - x0), y0 + 0.04 * (y1 - y0));
            panel.notes.push(Note {
                at,
                text: format!("ground {gap:.2} m below the lowest node (out of view)"),
                color: draw::GREY,
            });
        }
        panel.series.extend(members.series);
        draw::drawing_figure(vec![panel])
    }

    /// How far the ground plane lies below the structure's lowest node (m), in the side view
    /// with a ground: min over the nodes of n̂ · (p − p₀).
    fn ground_gap(&self, nodes: &[Vector3<f64>]) -> Option<f64> {
        let (p0, n) = self.ground?;
        if self.view != View::Side || n.norm() < 1e-12 {
            return None;
        }
        let n = n.normalize();
        nodes
            .iter()
            .map(|p| n.dot(&(p - p0)))
            .reduce(f64::min)
            .filter(|d| d.is_finite())
    }

    /// The ground's line in the picture, clipped to the window (side view only).
    fn ground_segment(&self, r: &Rotation3<f64>, w: Window) -> Option<Vec<(f64, f64)>> {
        let (p, n) = self.ground?;
        if self.view != View::Side {
            return None;
        }
        let (p, n) = (r * p, r * n);
        // n_y (y − p_y) + n_z (z − p_z) = 0 in the (y, z) plane: direction (n_z, −n_y)
        let d = (n.z, -n.y);
        if d.0.hypot(d.1) < 1e-12 {
            return None;
        }
        clip((p.y, p.z), d, w)
    }
}

fn bounds(points: &[(f64, f64)]) -> Window {
    points
        .iter()
        .fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |a, &(x, y)| {
            (a.0.min(x), a.1.max(x), a.2.min(y), a.3.max(y))
        })
}

fn padded((x0, x1, y0, y1): Window, f: f64) -> Window {
    let pad = f * (x1 - x0).max(y1 - y0).max(1e-9);
    (x0 - pad, x1 + pad, y0 - pad, y1 + pad)
}

/// The part of the line through `p` along `d` inside the window (Liang–Barsky).
fn clip(p: (f64, f64), d: (f64, f64), (x0, x1, y0, y1): Window) -> Option<Vec<(f64, f64)>> {
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for (q, dq, a, b) in [(p.0, d.0, x0, x1), (p.1, d.1, y0, y1)] {
        if dq.abs() < 1e-15 {
            if q < a || q > b {
                return None;
            }
            continue;
        }
        let (s0, s1) = ((a - q) / dq, (b - q) / dq);
        lo = lo.max(s0.min(s1));
        hi = hi.min(s0.max(s1));
    }
    (lo < hi).then(|| {
        vec![
            (p.0 + lo * d.0, p.1 + lo * d.1),
            (p.0 + hi * d.0, p.1 + hi * d.1),
        ]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_fps_times_duration_spread_over_the_run() {
        let s = AnimationSpec::new(Some(4.0), Some(2.0)).unwrap();
        assert_eq!(s.frames(), 8);
        let t = s.times(7.0);
        assert_eq!((t.len(), t[0], t[7]), (8, 0.0, 7.0));
        assert!(AnimationSpec::new(Some(0.0), None).is_err());
        assert!(AnimationSpec::new(Some(10.0), Some(0.1)).is_err());
        assert!(AnimationSpec::new(Some(10.0), Some(f64::NAN)).is_err());
    }

    #[test]
    fn the_ground_is_clipped_to_the_window() {
        let s = clip((0.0, 0.0), (1.0, -1.0), (-2.0, 2.0, -1.0, 1.0)).unwrap();
        assert_eq!(s, vec![(-1.0, 1.0), (1.0, -1.0)]);
        assert!(clip((0.0, 5.0), (1.0, 0.0), (-1.0, 1.0, -1.0, 1.0)).is_none());
    }

    #[test]
    fn a_sample_past_several_wanted_times_stands_for_each() {
        let dir = tempfile::tempdir().unwrap();
        let sink =
            AnimationSink::open(&dir.path().join("a.gif"), 10.0, Default::default()).unwrap();
        let scenery = Scenery {
            title: "bar".into(),
            bars: vec![[0, 1]],
            strings: vec![],
            ground: Some((Vector3::zeros(), Vector3::z())),
            view: View::Side,
            tilt: 0.2,
            along_y: false,
            camera: Camera::Fixed,
        };
        let spec = AnimationSpec::new(Some(5.0), Some(1.0)).unwrap();
        let mut a = Animation::new(sink, scenery, &spec, 1.0);
        let nodes = |z: f64| [Vector3::new(0.0, 0.0, z), Vector3::new(0.0, 1.0, z + 1.0)];
        for (t, z) in [(0.0, 1.0), (0.6, 0.5), (1.0, 0.0)] {
            a.frame(t, &nodes(z)).unwrap();
        }
        assert_eq!(a.kept(), 5);
        assert_eq!(a.finish().unwrap(), 5);
    }

    #[test]
    fn a_structure_followed_out_of_sight_of_the_ground_says_how_far_it_is() {
        let scenery = Scenery {
            title: "wheel".into(),
            bars: vec![[0, 1]],
            strings: vec![],
            // a slope of 30° through the origin, its normal up the slope's face
            ground: Some((Vector3::zeros(), Vector3::new(0.0, -0.5, 3f64.sqrt() / 2.0))),
            view: View::Side,
            tilt: 0.0,
            along_y: false,
            camera: Camera::Follow,
        };
        // a bar 3 m above the slope (lowest node), the window around it only
        let n = Vector3::new(0.0, -0.5, 3f64.sqrt() / 2.0);
        let low = 3.0 * n;
        let nodes = [low, low + Vector3::new(0.0, 0.3, 0.4)];
        assert!((scenery.ground_gap(&nodes).unwrap() - 3.0).abs() < 1e-12);
        let window = (low.y - 0.5, low.y + 0.8, low.z - 0.5, low.z + 0.8);
        let figure = scenery.frame(1.0, &nodes, window);
        let panel = &figure.panels[0];
        assert!(panel.series.iter().all(|s| s.label != "ground"));
        assert_eq!(panel.notes.len(), 1);
        assert!(panel.notes[0].text.starts_with("ground 3.00 m below"));
        // in view, the ground is drawn and no note is needed
        let wide = (-5.0, 5.0, -5.0, 5.0);
        let figure = scenery.frame(1.0, &nodes, wide);
        assert!(figure.panels[0].series.iter().any(|s| s.label == "ground"));
        assert!(figure.panels[0].notes.is_empty());
    }
}
