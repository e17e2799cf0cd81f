//! MuJoCo's MJCF: a structure written as a MuJoCo model ([`to_mjcf`], [`scene_to_mjcf`];
//! `tensegrity export mjcf`), by hand (no XML crate: every name is generated, the scene's
//! name escaped).
//!
//! The mapping, item by item:
//!
//! - **bar k** → `<body name="bark">` with a `<freejoint/>`, placed at the bar's midpoint and
//!   turned so that its local z axis runs along the bar (start node at z = −l/2, end node at
//!   z = +l/2), with an explicit `<inertial>`: the bar's mass m ([`Structure::bar_mass`]) and
//!   the slender-rod inertia m l²/12 about the two transverse axes, and ½ m r² (r the
//!   capsule's radius, at most m l²/12) about its axis (MuJoCo needs a positive value; this
//!   project's bars have no spin, and nothing here turns one about its axis but ground
//!   friction). A capsule geom (the bar's `radius`, else [`RADIUS_FRACTION`] of its length)
//!   with `mass="0"`, so it shows the bar and touches the ground without changing the inertia;
//!   a `<site>` at each end;
//! - **node i** → the site `ni`: the end of the first bar at the node, or, for a node on no
//!   bar, a site on the world body. The ends of the other bars at a shared node (a class-k
//!   joint) are the sites `ni_bark`, tied to the bar before by `<equality><connect>` (anchor
//!   at the node: a spherical joint, as this project's coincidence constraints); a node held
//!   in x, y and z ties its first bar's end to the world (`<connect>` without `body2`);
//! - **string k** → `<tendon><spatial name="sk">` between its two nodes' sites, with
//!   `stiffness` k (N/m), `damping` c (N·s/m) and `springlength="0 s0"`: MuJoCo's dead band,
//!   no spring force for lengths between 0 and the rest length s0, so tension k (‖s‖ − s0)
//!   above s0 and none below, the tension-only law of the dynamics (a missing rest length is
//!   the drawn length). MuJoCo's tendon damping acts on a slack string too (this project's
//!   only while taut): the two agree at rest, not in a slack string's motion;
//! - **cluster k** → a spatial tendon `ck` through the sites of all its nodes in order (a
//!   frictionless pulley at each inner node: one tension along all its segments), the
//!   cluster's stiffness, damping and rest length (dead band as a string's);
//! - gravity → `<option gravity>` (zero without one: MuJoCo's default is −9.81 z); the
//!   time step from [`MjcfOptions::timestep`]; the equality constraints stiffened
//!   (`solref`, `solimp`) so that their give under load stays far below 10⁻³ m;
//! - a ground ([`MjcfOptions::ground`]) → a plane geom; only the capsules touch it
//!   (`contype`/`conaffinity`: bars never touch each other), with the given friction and
//!   MuJoCo's own soft contact (not this project's penalty or thesis model).
//!
//! Refused, with an [`IoError::InvalidModel`] naming the item: a bar without a mass, a
//! string or cluster without a stiffness, a pulley with friction (a spatial tendon is
//! frictionless), a support held in only some directions, along directions of its own or by
//! a spring (MuJoCo's `connect` holds all three), a free node on no bar that a string touches
//! (it has no mass: MuJoCo needs a body), a load (MJCF has no constant force: MuJoCo applies
//! one at run time, through `data.xfrc_applied`), an initial velocity (the model starts at
//! rest), and, from a scene ([`scene_to_mjcf`]), the keys of the elastic models, a load
//! path's drivers and `[[actuation]]` tables.

use crate::error::{IoError, Result};
use crate::scene::Scene;
use nalgebra::{Unit, UnitQuaternion, Vector3};
use std::fmt::Write;
use tensegrity_core::Structure;

/// The time step MuJoCo integrates with when none is given (s).
pub const DEFAULT_TIMESTEP: f64 = 1e-3;

/// A bar's capsule radius when the bar has none, as a fraction of its length.
pub const RADIUS_FRACTION: f64 = 0.01;

/// The equality constraints' `solref` (time constant, damping ratio) and `solimp`: stiffer
/// than MuJoCo's defaults (0.02 s, impedance 0.9 to 0.95), so that a connect gives less than
/// 10⁻⁴ m under the loads of a metre-sized structure.
const EQUALITY_SOLREF: &str = "0.002 1";
const EQUALITY_SOLIMP: &str = "0.9999 0.9999 0.001 0.5 2";

/// A ground plane of the exported model.
#[derive(Debug, Clone, PartialEq)]
pub struct MjcfGround {
    /// A point of the plane (m).
    pub point: [f64; 3],
    /// Its outward normal (any length but zero).
    pub normal: [f64; 3],
    /// The sliding friction coefficient MuJoCo uses between the capsules and the plane.
    pub friction: f64,
}

impl MjcfGround {
    /// The horizontal plane z = `height` with MuJoCo's default friction 1.
    ///
    /// ```
    /// use tensegrity_io::mjcf::MjcfGround;
    /// assert_eq!(MjcfGround::height(0.5).point, [0.0, 0.0, 0.5]);
    /// ```
    pub fn height(height: f64) -> Self {
        Self {
            point: [0.0, 0.0, height],
            normal: [0.0, 0.0, 1.0],
            friction: 1.0,
        }
    }
}

/// What the export needs beside the structure.
#[derive(Debug, Clone, PartialEq)]
pub struct MjcfOptions {
    /// The name of the source (a scene file), for the model's name, its header and errors.
    pub source: String,
    /// MuJoCo's time step (s).
    pub timestep: f64,
    /// A ground plane; `None`: none ([`scene_to_mjcf`] then takes the scene's `[ground]`).
    pub ground: Option<MjcfGround>,
}

impl Default for MjcfOptions {
    fn default() -> Self {
        Self {
            source: "structure".to_string(),
            timestep: DEFAULT_TIMESTEP,
            ground: None,
        }
    }
}

/// The MJCF model of a scene: its structure ([`to_mjcf`]), with the scene's `[ground]` plane
/// and `mu_static` when `options` gives no ground (its contact model, stiffness and node list
/// are MuJoCo's own business). Refuses what the rigid-bar model of MJCF would ignore: an
/// elastic scene or a key of the elastic models (a string's `mass`, `[[masses]]`, a bar's
/// `rest_length`), a load path's drivers (`rest_length_change`, a support's
/// `displacement`) and `[[actuation]]` tables, naming the first.
///
/// ```
/// use tensegrity_io::mjcf::{scene_to_mjcf, MjcfOptions};
/// use tensegrity_io::scene::Scene;
/// let text = "nodes = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]\n[[bars]]\nnodes = [0, 1]\nmass = 1.0\n\
///             [[supports]]\nnode = 0\n[ground]\npoint = [0.0, 0.0, -1.0]\nstiffness = 1e4\n";
/// let scene = Scene::from_str_named(text, "pole.toml")?;
/// let xml = scene_to_mjcf(&scene, &MjcfOptions::default())?;
/// assert!(xml.contains(r#"<geom name="ground" type="plane" pos="0 0 -1""#));
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn scene_to_mjcf(scene: &Scene, options: &MjcfOptions) -> Result<String> {
    let file = &scene.file;
    let refuse = |item: String, reason: &str| IoError::InvalidModel {
        file: options.source.clone(),
        item,
        reason: reason.to_string(),
    };
    if file.is_elastic() {
        return Err(refuse(
            "scene".into(),
            "it is run by the elastic dynamics (elastic bars or point masses); the MJCF export writes rigid bars",
        ));
    }
    if let Some(key) = file.elastic_keys().into_iter().next() {
        return Err(refuse(key, "is read by the elastic models only; the MJCF export of rigid bars would ignore it: remove it"));
    }
    if let Some(key) = file.driver_keys().into_iter().next() {
        return Err(refuse(
            key,
            "drives a load path (tensegrity solve); MJCF has no such driver: remove it",
        ));
    }
    if !file.actuation.is_empty() {
        return Err(refuse(
            "actuation 0".into(),
            "a time table has no MJCF element: drive the tendon's springlength (model.tendon_lengthspring) from your script and remove the table",
        ));
    }
    let mut options = options.clone();
    if options.ground.is_none() {
        options.ground = file.ground.as_ref().map(|g| {
            let g = g.get_ref();
            MjcfGround {
                point: g.point,
                normal: g.normal,
                friction: g.mu_static.unwrap_or(0.0),
            }
        });
    }
    to_mjcf(&scene.structure, &options)
}

/// Where a node lives in the model.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Home {
    /// On the bars listed (its first bar carries the site `ni`).
    Bars,
    /// A site on the world body.
    World,
}

/// A bar as placed in the model.
struct BarPose {
    centre: Vector3<f64>,
    rotation: UnitQuaternion<f64>,
    half: f64,
    mass: f64,
    radius: f64,
}

/// The MJCF text of `structure` (module docs for the mapping and what is refused).
///
/// ```
/// use tensegrity_core::{Bar, StringMember, Structure, Support};
/// use tensegrity_io::mjcf::{to_mjcf, MjcfOptions};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [0.0, 0.0, 2.0], [1.0, 0.0, 2.0]])
///     .bar(Bar::new(0, 1).mass(3.0))
///     .string(StringMember::new(1, 2).stiffness(100.0).rest_length(0.9))
///     .support(Support::pinned(0))
///     .support(Support::pinned(2))
///     .build()?;
/// let xml = to_mjcf(&s, &MjcfOptions::default())?;
/// assert!(xml.contains(r#"<inertial pos="0 0 0" mass="3" diaginertia="1 1 "#)); // m l²/12
/// assert!(xml.contains(r#"<spatial name="s0" stiffness="100" damping="0" springlength="0 0.9">"#));
/// assert!(xml.contains(r#"<connect name="n0_world" body1="bar0" anchor="0 0 -1"/>"#));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn to_mjcf(structure: &Structure, options: &MjcfOptions) -> Result<String> {
    let bad = |item: String, reason: String| IoError::InvalidModel {
        file: options.source.clone(),
        item,
        reason,
    };
    check_options(options, &bad)?;
    refuse_loads_and_motion(structure, &bad)?;
    let pinned = pinned_nodes(structure, &bad)?;
    let copies = bar_ends(structure);
    let homes = node_homes(structure, &copies, &pinned, &bad)?;
    let poses = bar_poses(structure, &bad)?;
    let mut xml = String::new();
    header(&mut xml, structure, options, &copies, &homes);
    let name = escape(&options.source);
    let _ = writeln!(xml, "<mujoco model=\"{name}\">");
    preamble(&mut xml, structure, options);
    worldbody(&mut xml, structure, options, &homes, &copies, &poses);
    equalities(&mut xml, &copies, &pinned, &poses);
    tendons(&mut xml, structure, &bad)?;
    xml.push_str("</mujoco>\n");
    Ok(xml)
}

type Bad<'a> = dyn Fn(String, String) -> IoError + 'a;

fn check_options(options: &MjcfOptions, bad: &Bad) -> Result<()> {
    if !(options.timestep.is_finite() && options.timestep > 0.0) {
        return Err(bad(
            "timestep".into(),
            format!("must be positive and finite, got {}", options.timestep),
        ));
    }
    if let Some(g) = &options.ground {
        let finite = g.point.iter().chain(&g.normal).all(|v| v.is_finite());
        if !finite || Vector3::from(g.normal).norm() == 0.0 {
            return Err(bad(
                "ground".into(),
                "its point and normal must be finite and the normal non-zero".into(),
            ));
        }
        if !(g.friction.is_finite() && g.friction >= 0.0) {
            return Err(bad(
                "ground".into(),
                format!(
                    "friction must be non-negative and finite, got {}",
                    g.friction
                ),
            ));
        }
    }
    Ok(())
}

fn refuse_loads_and_motion(structure: &Structure, bad: &Bad) -> Result<()> {
    if let Some(load) = structure.loads().first() {
        return Err(bad(
            format!("load 0 (node {})", load.node),
            "MJCF has no constant nodal force: MuJoCo applies a body force at run time \
             (data.xfrc_applied: a force and a torque at the body's centre of mass); remove \
             the loads and apply them in your script"
                .into(),
        ));
    }
    let moving = structure
        .velocities()
        .and_then(|v| v.iter().position(|v| *v != Vector3::zeros()));
    if let Some(i) = moving {
        return Err(bad(
            format!("node {i}"),
            "has an initial velocity; the MJCF model starts at rest (set data.qvel in your \
             script and remove the velocities)"
                .into(),
        ));
    }
    Ok(())
}

/// Whether each node is held in x, y and z; an error for any other support.
fn pinned_nodes(structure: &Structure, bad: &Bad) -> Result<Vec<bool>> {
    let mut pinned = vec![false; structure.n_nodes()];
    for (k, s) in structure.supports().iter().enumerate() {
        let item = || format!("support {k} (node {})", s.node);
        if s.is_elastic() {
            return Err(bad(item(), "is a spring; MJCF's connect holds a point rigidly: give the support no stiffness, or model the spring as a string to a pinned node".into()));
        }
        if !s.along.is_empty() {
            return Err(bad(item(), "holds the node along directions of its own; MJCF's connect holds all three: pin the node in x, y and z".into()));
        }
    }
    for (i, fixed) in structure.fixed_dofs().into_iter().enumerate() {
        if fixed == [true; 3] {
            pinned[i] = true;
        } else if fixed.contains(&true) {
            let k = structure
                .supports()
                .iter()
                .position(|s| s.node == i)
                .unwrap_or(0);
            return Err(bad(
                format!("support {k} (node {i})"),
                "holds the node in some directions only; MJCF's connect holds all three (a partial hold would need a slide joint on a body of its own): pin it in x, y and z".into(),
            ));
        }
    }
    Ok(pinned)
}

/// For each node, the bars ending there (bar index, end 0 or 1), in bar order.
fn bar_ends(structure: &Structure) -> Vec<Vec<(usize, usize)>> {
    let mut copies = vec![Vec::new(); structure.n_nodes()];
    for (k, b) in structure.bars().iter().enumerate() {
        copies[b.nodes[0]].push((k, 0));
        copies[b.nodes[1]].push((k, 1));
    }
    copies
}

fn node_homes(
    structure: &Structure,
    copies: &[Vec<(usize, usize)>],
    pinned: &[bool],
    bad: &Bad,
) -> Result<Vec<Home>> {
    let mut homes = Vec::with_capacity(copies.len());
    for (i, c) in copies.iter().enumerate() {
        if !c.is_empty() {
            homes.push(Home::Bars);
            continue;
        }
        let touched = structure.strings().iter().any(|s| s.nodes.contains(&i))
            || structure.clusters().iter().any(|c| c.nodes.contains(&i));
        if touched && !pinned[i] {
            return Err(bad(
                format!("node {i}"),
                "is free and on no bar: it has no mass, and MuJoCo moves bodies with mass only; pin it in x, y and z or put it on a bar".into(),
            ));
        }
        homes.push(Home::World);
    }
    Ok(homes)
}

fn bar_poses(structure: &Structure, bad: &Bad) -> Result<Vec<BarPose>> {
    let nodes = structure.nodes();
    let mut poses = Vec::with_capacity(structure.n_bars());
    for (k, bar) in structure.bars().iter().enumerate() {
        let mass = structure
            .bar_mass(k)
            .filter(|m| m.is_finite() && *m > 0.0)
            .ok_or_else(|| {
                bad(
                    format!("bar {k}"),
                    "has no mass (give it a mass, or a material and a radius)".into(),
                )
            })?;
        let [a, b] = bar.nodes;
        let axis = nodes[b] - nodes[a];
        let length = axis.norm();
        let rotation =
            UnitQuaternion::rotation_between_axis(&Vector3::z_axis(), &Unit::new_normalize(axis))
                .unwrap_or_else(|| {
                    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
                });
        poses.push(BarPose {
            centre: 0.5 * (nodes[a] + nodes[b]),
            rotation,
            half: 0.5 * length,
            mass,
            radius: bar
                .radius
                .filter(|r| r.is_finite() && *r > 0.0)
                .unwrap_or(RADIUS_FRACTION * length),
        });
    }
    Ok(poses)
}

/// The comment at the top: the source and the mapping, and where each node is.
fn header(
    xml: &mut String,
    structure: &Structure,
    options: &MjcfOptions,
    copies: &[Vec<(usize, usize)>],
    homes: &[Home],
) {
    let source = options.source.replace("--", "- -");
    let _ = writeln!(
        xml,
        "<!-- Exported by `tensegrity export mjcf` from {source}."
    );
    xml.push_str(concat!(
        "     Bar k: body `bark` with a free joint, at the bar's midpoint, local z along the bar\n",
        "     (start node at z = -l/2), inertial mass m and m l^2/12 about both transverse axes,\n",
        "     a massless capsule, a site at each end. Node i: site `ni` (its first bar's end, or\n",
        "     on the world body); other bars' ends at a shared node: sites `ni_bark`, tied by\n",
        "     <connect>; a node pinned in x, y, z: its first bar's end connected to the world.\n",
        "     String k: spatial tendon `sk` (stiffness k, damping c, springlength \"0 s0\": no force\n",
        "     below the rest length s0); cluster k: spatial tendon `ck` through its nodes' sites.\n",
    ));
    let (nb, ns, nc) = (
        structure.n_bars(),
        structure.n_strings(),
        structure.clusters().len(),
    );
    let _ = writeln!(
        xml,
        "     {} nodes, {nb} bars, {ns} strings, {nc} clusters.",
        homes.len()
    );
    for (i, home) in homes.iter().enumerate() {
        let at = match (home, copies[i].first()) {
            (Home::Bars, Some(&(k, e))) => format!("end {e} of bar {k}"),
            _ => "world".to_string(),
        };
        let _ = writeln!(xml, "     n{i}: {at}");
    }
    xml.push_str("-->\n");
}

fn preamble(xml: &mut String, structure: &Structure, options: &MjcfOptions) {
    let g = structure.gravity().unwrap_or_else(Vector3::zeros);
    xml.push_str("  <compiler angle=\"radian\" autolimits=\"true\"/>\n");
    let _ = writeln!(
        xml,
        "  <option timestep=\"{}\" gravity=\"{}\" integrator=\"implicitfast\"/>",
        num(options.timestep),
        vec3(&g)
    );
    let _ = writeln!(
        xml,
        "  <default>\n    <geom contype=\"0\" conaffinity=\"0\" rgba=\"0.55 0.35 0.2 1\"/>\n    \
         <site rgba=\"0.2 0.2 0.2 1\"/>\n    <tendon width=\"0.004\" rgba=\"0.1 0.3 0.8 1\"/>\n    \
         <equality solref=\"{EQUALITY_SOLREF}\" solimp=\"{EQUALITY_SOLIMP}\"/>\n  </default>"
    );
}

fn worldbody(
    xml: &mut String,
    structure: &Structure,
    options: &MjcfOptions,
    homes: &[Home],
    copies: &[Vec<(usize, usize)>],
    poses: &[BarPose],
) {
    xml.push_str("  <worldbody>\n");
    if let Some(g) = &options.ground {
        let normal = Vector3::from(g.normal).normalize();
        let _ = writeln!(
            xml,
            "    <geom name=\"ground\" type=\"plane\" pos=\"{}\" zaxis=\"{}\" size=\"0 0 1\" contype=\"0\" conaffinity=\"1\" friction=\"{} 0.005 0.0001\" rgba=\"0.8 0.8 0.8 1\"/>",
            vec3(&Vector3::from(g.point)),
            vec3(&normal),
            num(g.friction)
        );
    }
    let contype = u8::from(options.ground.is_some());
    let nodes = structure.nodes();
    for (i, home) in homes.iter().enumerate() {
        if *home == Home::World {
            let _ = writeln!(
                xml,
                "    <site name=\"n{i}\" pos=\"{}\" size=\"0.01\"/>",
                vec3(&nodes[i])
            );
        }
    }
    for (k, (bar, p)) in structure.bars().iter().zip(poses).enumerate() {
        let q = p.rotation.quaternion();
        let _ = writeln!(
            xml,
            "    <body name=\"bar{k}\" pos=\"{}\" quat=\"{} {} {} {}\">",
            vec3(&p.centre),
            num(q.w),
            num(q.i),
            num(q.j),
            num(q.k)
        );
        let transverse = p.mass * (2.0 * p.half).powi(2) / 12.0;
        let axial = (0.5 * p.mass * p.radius * p.radius).min(transverse);
        let _ = writeln!(
            xml,
            "      <freejoint name=\"bar{k}\"/>\n      <inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{t} {t} {}\"/>",
            num(p.mass),
            num(axial),
            t = num(transverse)
        );
        let h = num(p.half);
        let _ = writeln!(
            xml,
            "      <geom name=\"bar{k}\" type=\"capsule\" size=\"{}\" fromto=\"0 0 -{h} 0 0 {h}\" mass=\"0\" contype=\"{contype}\" conaffinity=\"0\"/>",
            num(p.radius)
        );
        for (e, node) in bar.nodes.iter().enumerate() {
            let name = site_name(*node, k, copies);
            let z = if e == 0 { format!("-{h}") } else { h.clone() };
            let _ = writeln!(
                xml,
                "      <site name=\"{name}\" pos=\"0 0 {z}\" size=\"{}\"/>",
                num(1.5 * p.radius)
            );
        }
        xml.push_str("    </body>\n");
    }
    xml.push_str("  </worldbody>\n");
}

/// The site of bar `k`'s end at `node`: `ni` for the node's first bar, `ni_bark` otherwise.
fn site_name(node: usize, k: usize, copies: &[Vec<(usize, usize)>]) -> String {
    match copies[node].first() {
        Some(&(first, _)) if first != k => format!("n{node}_bar{k}"),
        _ => format!("n{node}"),
    }
}

fn anchor(p: &BarPose, end: usize) -> String {
    match end {
        0 => format!("0 0 -{}", num(p.half)),
        _ => format!("0 0 {}", num(p.half)),
    }
}

fn equalities(
    xml: &mut String,
    copies: &[Vec<(usize, usize)>],
    pinned: &[bool],
    poses: &[BarPose],
) {
    let mut body = String::new();
    for (i, c) in copies.iter().enumerate() {
        if let (true, Some(&(k, e))) = (pinned[i], c.first()) {
            let _ = writeln!(
                body,
                "    <connect name=\"n{i}_world\" body1=\"bar{k}\" anchor=\"{}\"/>",
                anchor(&poses[k], e)
            );
        }
        for pair in c.windows(2) {
            let ((j, _), (k, e)) = (pair[0], pair[1]);
            let _ = writeln!(
                body,
                "    <connect name=\"n{i}_bar{j}_bar{k}\" body1=\"bar{k}\" body2=\"bar{j}\" anchor=\"{}\"/>",
                anchor(&poses[k], e)
            );
        }
    }
    if !body.is_empty() {
        let _ = write!(xml, "  <equality>\n{body}  </equality>\n");
    }
}

fn tendons(xml: &mut String, structure: &Structure, bad: &Bad) -> Result<()> {
    let nodes = structure.nodes();
    let mut body = String::new();
    for (k, s) in structure.strings().iter().enumerate() {
        let stiffness = s.stiffness.ok_or_else(|| {
            bad(
                format!("string {k}"),
                "has no stiffness (give it one, in N/m)".into(),
            )
        })?;
        let [a, b] = s.nodes;
        let rest = s.rest_length.unwrap_or((nodes[b] - nodes[a]).norm());
        spatial(
            &mut body,
            &format!("s{k}"),
            stiffness,
            s.damping,
            rest,
            &s.nodes,
        );
    }
    for (k, c) in structure.clusters().iter().enumerate() {
        if !c.is_frictionless() {
            return Err(bad(
                format!("cluster {k}"),
                "has pulley friction; MuJoCo's spatial tendon slides over its sites without friction: remove its friction".into(),
            ));
        }
        let stiffness = c.stiffness.ok_or_else(|| {
            bad(
                format!("cluster {k}"),
                "has no stiffness (give it one, in N/m)".into(),
            )
        })?;
        let rest = c.rest_length.unwrap_or_else(|| c.length(nodes));
        spatial(
            &mut body,
            &format!("c{k}"),
            stiffness,
            c.damping,
            rest,
            &c.nodes,
        );
    }
    if !body.is_empty() {
        let _ = write!(xml, "  <tendon>\n{body}  </tendon>\n");
    }
    Ok(())
}

fn spatial(out: &mut String, name: &str, k: f64, c: f64, rest: f64, nodes: &[usize]) {
    let _ = writeln!(
        out,
        "    <spatial name=\"{name}\" stiffness=\"{}\" damping=\"{}\" springlength=\"0 {}\">",
        num(k),
        num(c),
        num(rest)
    );
    for n in nodes {
        let _ = writeln!(out, "      <site site=\"n{n}\"/>");
    }
    out.push_str("    </spatial>\n");
}

/// A number as MuJoCo reads it: the shortest text that reads back to the same f64, with an
/// exponent outside 10⁻⁵ … 10¹⁶.
fn num(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else if (1e-5..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

fn vec3(v: &Vector3<f64>) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

/// `text` as an XML attribute value.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::{Bar, Cluster, StringMember, Support};

    fn two_bars() -> tensegrity_core::StructureBuilder {
        Structure::builder()
            .nodes([
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 2.0],
                [2.0, 0.0, 2.0],
                [1.0, 1.0, 0.0],
            ])
            .bar(Bar::new(0, 1).mass(3.0).radius(0.05))
            .bar(Bar::new(1, 2).mass(1.5))
            .string(StringMember::new(2, 3).stiffness(50.0).damping(0.5))
            .support(Support::pinned(0))
            .support(Support::pinned(3))
    }

    fn parse(xml: &str) -> roxmltree::Document<'_> {
        roxmltree::Document::parse(xml).expect("well-formed XML")
    }

    fn attr<'a>(doc: &'a roxmltree::Document, tag: &str, name: &str, key: &str) -> &'a str {
        doc.descendants()
            .find(|n| n.has_tag_name(tag) && n.attribute("name") == Some(name))
            .and_then(|n| n.attribute(key))
            .unwrap_or_else(|| panic!("<{tag} name={name}> has no {key}"))
    }

    fn numbers(text: &str) -> Vec<f64> {
        text.split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect()
    }

    #[test]
    fn bars_become_bodies_at_their_midpoints_with_the_rod_inertia() {
        let xml = to_mjcf(&two_bars().build().unwrap(), &MjcfOptions::default()).unwrap();
        let doc = parse(&xml);
        assert_eq!(numbers(attr(&doc, "body", "bar1", "pos")), [1.0, 0.0, 2.0]);
        let inertial = doc
            .descendants()
            .filter(|n| n.has_tag_name("inertial"))
            .nth(1)
            .unwrap();
        assert_eq!(inertial.attribute("mass"), Some("1.5"));
        let i = numbers(inertial.attribute("diaginertia").unwrap());
        assert!((i[0] - 1.5 * 4.0 / 12.0).abs() < 1e-15 && i[0] == i[1]);
        assert!(i[2] > 0.0 && i[2] < i[0]);
        // bar 1 runs along +x: its local z turned onto x (w = cos 45°, about +y)
        let q = numbers(attr(&doc, "body", "bar1", "quat"));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (q[0] - h).abs() < 1e-15 && (q[2] - h).abs() < 1e-15,
            "{q:?}"
        );
        assert_eq!(attr(&doc, "geom", "bar0", "size"), "0.05");
        assert_eq!(attr(&doc, "geom", "bar1", "size"), "0.02");
    }

    #[test]
    fn shared_and_pinned_nodes_become_connects() {
        let xml = to_mjcf(&two_bars().build().unwrap(), &MjcfOptions::default()).unwrap();
        let doc = parse(&xml);
        assert_eq!(attr(&doc, "connect", "n0_world", "anchor"), "0 0 -1");
        assert_eq!(attr(&doc, "connect", "n1_bar0_bar1", "body1"), "bar1");
        assert_eq!(attr(&doc, "connect", "n1_bar0_bar1", "anchor"), "0 0 -1");
        assert_eq!(attr(&doc, "site", "n1_bar1", "pos"), "0 0 -1");
        assert_eq!(attr(&doc, "site", "n3", "pos"), "1 1 0");
        // the string: its drawn length as the rest length (no prestress)
        let s = attr(&doc, "spatial", "s0", "springlength");
        assert_eq!(numbers(s), [0.0, 6f64.sqrt()]);
        assert_eq!(attr(&doc, "spatial", "s0", "damping"), "0.5");
    }

    #[test]
    fn clusters_run_through_every_node_site() {
        let s = Structure::builder()
            .nodes([
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 1.0],
                [1.0, 0.0, 0.0],
            ])
            .bar(Bar::new(0, 1).mass(1.0))
            .bar(Bar::new(3, 2).mass(1.0))
            .cluster(Cluster::new([0, 2, 1, 3]).stiffness(10.0).rest_length(2.0))
            .support(Support::pinned(0))
            .support(Support::pinned(3))
            .build()
            .unwrap();
        let xml = to_mjcf(&s, &MjcfOptions::default()).unwrap();
        let doc = parse(&xml);
        let c0 = doc
            .descendants()
            .find(|n| n.attribute("name") == Some("c0"))
            .unwrap();
        let sites: Vec<_> = c0.children().filter_map(|n| n.attribute("site")).collect();
        assert_eq!(sites, ["n0", "n2", "n1", "n3"]);
        assert_eq!(c0.attribute("springlength"), Some("0 2"));
        let mut c = s.clusters()[0].clone();
        c.friction = Some(vec![0.2, 0.0]);
        let s = Structure::builder()
            .nodes(s.nodes().iter().map(|n| [n.x, n.y, n.z]))
            .bars(s.bars().iter().cloned())
            .cluster(c)
            .support(Support::pinned(0))
            .build()
            .unwrap();
        let e = to_mjcf(&s, &MjcfOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("cluster 0: has pulley friction"), "{e}");
    }

    #[test]
    fn what_mjcf_cannot_say_is_refused_naming_the_item() {
        let options = MjcfOptions::default();
        let err = |s: Structure| to_mjcf(&s, &options).unwrap_err().to_string();
        let partial = two_bars()
            .support(Support::directions(2, [false, false, true]))
            .build()
            .unwrap();
        assert!(err(partial).contains("support 2 (node 2): holds the node in some directions only"));
        let free = Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0]])
            .bar(Bar::new(0, 1).mass(1.0))
            .string(StringMember::new(1, 2).stiffness(1.0))
            .build()
            .unwrap();
        assert!(err(free).contains("node 2: is free and on no bar"));
        let loaded = two_bars().load(2, [0.0, 0.0, -1.0]).build().unwrap();
        assert!(err(loaded).contains("load 0 (node 2): MJCF has no constant nodal force"));
        let massless = Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
            .bar(Bar::new(0, 1))
            .build()
            .unwrap();
        assert!(err(massless).contains("bar 0: has no mass"));
        let spring = two_bars()
            .support(Support::pinned(2).elastic(1e3))
            .build()
            .unwrap();
        assert!(err(spring).contains("support 2 (node 2): is a spring"));
        let bad_step = MjcfOptions {
            timestep: 0.0,
            ..MjcfOptions::default()
        };
        let e = to_mjcf(&two_bars().build().unwrap(), &bad_step).unwrap_err();
        assert!(e.to_string().contains("timestep: must be positive"), "{e}");
    }

    #[test]
    fn names_are_escaped_and_numbers_read_back() {
        assert_eq!(escape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&apos;");
        for x in [1e-20, 0.1, 1.0 / 3.0, -2.5e17, 7.0] {
            assert_eq!(num(x).parse::<f64>().unwrap(), x);
        }
        let options = MjcfOptions {
            source: "a<b>--c.toml".into(),
            ground: Some(MjcfGround::height(-0.5)),
            ..MjcfOptions::default()
        };
        let xml = to_mjcf(&two_bars().build().unwrap(), &options).unwrap();
        let doc = parse(&xml);
        assert_eq!(doc.root_element().attribute("model"), Some("a<b>--c.toml"));
        assert_eq!(attr(&doc, "geom", "ground", "pos"), "0 0 -0.5");
        assert_eq!(attr(&doc, "geom", "bar0", "contype"), "1");
    }
}
