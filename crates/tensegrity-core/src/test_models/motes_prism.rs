//! The MOTES anchor prism (the scene `examples/anchors/motes_prism.toml`): the equal-radius
//! Snelson prism of the thesis (radius 1 m, height 2 m, twist 30°), bars bottom i → top i+1
//! of 1 kg, massless strings (bottom ring, top ring, verticals) with k = 100 N/m and rest
//! lengths 90 % of their initial lengths; free, no gravity: it contracts and oscillates.
//!
//! Reference answer: the scene's final state after 5000 RK4 steps of 1 ms is checked against
//! an independent integrator in the workspace's `tests/anchors.rs`; here it is the fixture of
//! the class-1 step benchmark.

use crate::error::Result;
use crate::structure::{Bar, StringMember, Structure};

/// The MOTES anchor prism, node for node and digit for digit as its scene file.
pub fn motes_anchor_prism() -> Result<Structure> {
    let ring = 1.5588457268119895;
    let vertical = 1.85931139023812;
    Structure::builder()
        .nodes([
            [1.0, 0.0, 0.0],
            [-0.4999999999999998, 0.8660254037844387, 0.0],
            [-0.5000000000000004, -0.8660254037844384, 0.0],
            [0.8660254037844386, 0.5, 2.0],
            [-0.8660254037844385, 0.5000000000000003, 2.0],
            [-1.8369701987210297e-16, -1.0, 2.0],
        ])
        .bar(Bar::new(0, 4).mass(1.0))
        .bar(Bar::new(1, 5).mass(1.0))
        .bar(Bar::new(2, 3).mass(1.0))
        .string(StringMember::new(0, 1).stiffness(100.0).rest_length(ring))
        .string(StringMember::new(1, 2).stiffness(100.0).rest_length(ring))
        .string(
            StringMember::new(2, 0)
                .stiffness(100.0)
                .rest_length(1.55884572681199),
        )
        .string(StringMember::new(3, 4).stiffness(100.0).rest_length(ring))
        .string(
            StringMember::new(4, 5)
                .stiffness(100.0)
                .rest_length(1.5588457268119897),
        )
        .string(
            StringMember::new(5, 3)
                .stiffness(100.0)
                .rest_length(1.5588457268119897),
        )
        .string(
            StringMember::new(0, 3)
                .stiffness(100.0)
                .rest_length(vertical),
        )
        .string(
            StringMember::new(1, 4)
                .stiffness(100.0)
                .rest_length(1.8593113902381195),
        )
        .string(
            StringMember::new(2, 5)
                .stiffness(100.0)
                .rest_length(vertical),
        )
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scene's construction: every string's rest length is 90 % of its initial length
    /// (the digits of the scene file), the bars have 1 kg and no node is fixed.
    #[test]
    fn rest_lengths_are_ninety_percent_of_the_initial_lengths() {
        let s = motes_anchor_prism().unwrap();
        assert_eq!((s.n_bars(), s.n_strings()), (3, 9));
        for m in s.strings() {
            let [a, b] = m.nodes;
            let l = (s.nodes()[b] - s.nodes()[a]).norm();
            let rest = m.rest_length.unwrap();
            assert!(
                (rest - 0.9 * l).abs() < 1e-12,
                "{a}-{b}: {rest} against {l}"
            );
        }
        assert!(s.bars().iter().all(|b| b.mass == Some(1.0)));
        assert!(s.fixed_dofs().iter().all(|f| *f == [false; 3]));
    }
}
