//! [`to_toml`]: a structure written back as scene TOML; [`scene_to_toml`]: a scene's
//! structure with the keys its file holds beside it.

use super::{Scene, SceneFile};
use tensegrity_core::Structure;

/// Writes a structure as scene TOML that [`super::Scene::from_str_named`] reads back exactly
/// (shortest round-trip number formatting; user materials are written out in full).
///
/// ```
/// use tensegrity_io::scene::{to_toml, Scene};
/// use tensegrity_core::{Bar, StringMember, Structure, Support};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [0.1, 0.2, 0.3], [1.0 / 3.0, 0.0, 1.0], [0.0, 1.0, 0.0]])
///     .bar(Bar::new(0, 1).mass(2.0))
///     .string(StringMember::new(1, 2).stiffness(100.0).rest_length(0.5))
///     .string(StringMember::new(2, 0))
///     .support(Support::directions(0, [true, false, true]))
///     .support(Support::along(1, [[0.0, 0.6, 0.8]]).elastic(1e4))
///     .cluster(tensegrity_core::Cluster::new([0, 3, 2]).stiffness(50.0).friction([0.2]))
///     .load(2, [0.0, 0.0, -5.0])
///     .build()
///     .unwrap();
/// let back = Scene::from_str_named(&to_toml(&s), "round-trip").unwrap();
/// assert_eq!(back.structure, s);
/// ```
pub fn to_toml(structure: &Structure) -> String {
    write(structure, None)
}

/// [`to_toml`] of a scene's structure with the keys its file holds beside it (bars'
/// `rest_length`, `rest_length_change` and `elastic`, strings' `mass` and
/// `rest_length_change`, supports' `displacement`, the `[[masses]]`), read back exactly; not
/// its dynamics tables.
///
/// ```
/// use tensegrity_io::scene::{scene_to_toml, Scene, SceneArrays};
/// let text = "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n[[strings]]\nnodes = [0, 1]\n\
///             stiffness = 10.0\nmass = 0.5\nrest_length_change = -0.1\n[[supports]]\n\
///             node = 0\ndisplacement = [0.0, 0.0, 0.1]\n[[masses]]\nnode = 1\nmass = 2.0\n";
/// let scene = Scene::from_str_named(text, "net.toml")?;
/// let back = Scene::from_str_named(&scene_to_toml(&scene), "again")?;
/// assert_eq!(SceneArrays::of(&back), SceneArrays::of(&scene));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn scene_to_toml(scene: &Scene) -> String {
    write(&scene.structure, Some(&scene.file))
}

/// The writer of [`to_toml`] and [`scene_to_toml`].
fn write(structure: &Structure, file: Option<&SceneFile>) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let v3 = |v: &nalgebra::Vector3<f64>| format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z);
    out.push_str("nodes = [\n");
    for n in structure.nodes() {
        let _ = writeln!(out, "  {},", v3(n));
    }
    out.push_str("]\n");
    if let Some(vel) = structure.velocities() {
        out.push_str("velocities = [\n");
        for v in vel {
            let _ = writeln!(out, "  {},", v3(v));
        }
        out.push_str("]\n");
    }
    let mut names: Vec<&str> = structure
        .bars()
        .iter()
        .filter_map(|b| b.material.as_deref())
        .chain(
            structure
                .strings()
                .iter()
                .filter_map(|s| s.material.as_deref()),
        )
        .chain(
            structure
                .clusters()
                .iter()
                .filter_map(|c| c.material.as_deref()),
        )
        .collect();
    names.sort_unstable();
    names.dedup();
    for name in names {
        if let Some(m) = structure.materials().get(name) {
            let _ = write!(
                out,
                "\n[materials.{name}]\ndensity = {:?}\nyoungs_modulus = {:?}\nyield_strength = {:?}\n",
                m.density, m.youngs_modulus, m.yield_strength
            );
        }
    }
    for (k, b) in structure.bars().iter().enumerate() {
        let _ = write!(
            out,
            "\n[[bars]]\nnodes = [{}, {}]\n",
            b.nodes[0], b.nodes[1]
        );
        if let Some(m) = b.mass {
            let _ = writeln!(out, "mass = {m:?}");
        }
        if let Some(name) = &b.material {
            let _ = writeln!(out, "material = \"{name}\"");
        }
        if let Some(r) = b.radius {
            let _ = writeln!(out, "radius = {r:?}");
        }
        if let Some(spec) = file.and_then(|f| f.bars.get(k)).map(|b| b.get_ref()) {
            if let Some(l) = spec.rest_length {
                let _ = writeln!(out, "rest_length = {l:?}");
            }
            if let Some(d) = spec.rest_length_change {
                let _ = writeln!(out, "rest_length_change = {d:?}");
            }
            if let Some(e) = spec.elastic {
                let _ = writeln!(out, "elastic = {e}");
            }
        }
    }
    for (k, s) in structure.strings().iter().enumerate() {
        let _ = write!(
            out,
            "\n[[strings]]\nnodes = [{}, {}]\n",
            s.nodes[0], s.nodes[1]
        );
        if let Some(k) = s.stiffness {
            let _ = writeln!(out, "stiffness = {k:?}");
        }
        if let Some(s0) = s.rest_length {
            let _ = writeln!(out, "rest_length = {s0:?}");
        }
        if s.damping != 0.0 {
            let _ = writeln!(out, "damping = {:?}", s.damping);
        }
        if let Some(name) = &s.material {
            let _ = writeln!(out, "material = \"{name}\"");
        }
        if let Some(spec) = file.and_then(|f| f.strings.get(k)).map(|s| s.get_ref()) {
            if let Some(m) = spec.mass {
                let _ = writeln!(out, "mass = {m:?}");
            }
            if let Some(d) = spec.rest_length_change {
                let _ = writeln!(out, "rest_length_change = {d:?}");
            }
        }
    }
    for (k, c) in structure.clusters().iter().enumerate() {
        let nodes: Vec<String> = c.nodes.iter().map(usize::to_string).collect();
        let _ = write!(out, "\n[[clusters]]\nnodes = [{}]\n", nodes.join(", "));
        if let Some(k) = c.stiffness {
            let _ = writeln!(out, "stiffness = {k:?}");
        }
        if let Some(l0) = c.rest_length {
            let _ = writeln!(out, "rest_length = {l0:?}");
        }
        if c.damping != 0.0 {
            let _ = writeln!(out, "damping = {:?}", c.damping);
        }
        if let Some(mu) = &c.friction {
            let mu: Vec<String> = mu.iter().map(|m| format!("{m:?}")).collect();
            let _ = writeln!(out, "friction = [{}]", mu.join(", "));
        }
        if let Some(name) = &c.material {
            let _ = writeln!(out, "material = \"{name}\"");
        }
        let spec = file.and_then(|f| f.clusters.get(k)).map(|c| c.get_ref());
        if let Some(d) = spec.and_then(|c| c.rest_length_change) {
            let _ = writeln!(out, "rest_length_change = {d:?}");
        }
    }
    for (i, s) in structure.supports().iter().enumerate() {
        let _ = write!(out, "\n[[supports]]\nnode = {}\n", s.node);
        // `along` alone holds no axis; with axes too, they are written as flags
        let axes_default = if s.along.is_empty() {
            [true; 3]
        } else {
            [false; 3]
        };
        if s.fixed != axes_default {
            let _ = writeln!(
                out,
                "fixed = [{}, {}, {}]",
                s.fixed[0], s.fixed[1], s.fixed[2]
            );
        }
        if !s.along.is_empty() {
            let dirs: Vec<String> = s.along.iter().map(v3).collect();
            let _ = writeln!(out, "along = [{}]", dirs.join(", "));
        }
        if let Some(k) = s.stiffness {
            let _ = writeln!(out, "stiffness = {k:?}");
        }
        let moved = file.and_then(|f| f.supports.get(i)?.get_ref().displacement);
        if let Some(d) = moved {
            let _ = writeln!(out, "displacement = [{:?}, {:?}, {:?}]", d[0], d[1], d[2]);
        }
    }
    for m in file.iter().flat_map(|f| &f.masses).map(|m| m.get_ref()) {
        let _ = write!(
            out,
            "\n[[masses]]\nnode = {}\nmass = {:?}\n",
            m.node, m.mass
        );
    }
    for l in structure.loads() {
        let _ = write!(
            out,
            "\n[[loads]]\nnode = {}\nforce = {}\n",
            l.node,
            v3(&l.force)
        );
    }
    if let Some(g) = structure.gravity() {
        let _ = write!(out, "\n[gravity]\nacceleration = {}\n", v3(&g));
    }
    out
}
