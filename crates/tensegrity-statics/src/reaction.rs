//! A support reaction as the reports give it: the force the support exerts on its node (N),
//! which lies in the span of the support's held directions, and, for a support with `along`
//! directions, its components along each of them (r = Σ a_h d_h over all its held directions,
//! [`reaction_components`](crate::reaction_components)). The load solve
//! ([`report`](crate::report)) and the linear response ([`response`](crate::response)) report
//! their reactions in this one shape.

use nalgebra::Vector3;
use serde::Serialize;
use tensegrity_core::structure::Support;

/// A support reaction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reaction {
    /// The supported node.
    pub node: usize,
    /// Reaction force (N): in the span of the support's held directions (an elastic
    /// support's spring force).
    pub force: [f64; 3],
    /// For a support with `along` directions: the force along each of them (N), from
    /// `force` = Σ a_h d_h over all its held directions (flagged axes, then `along`;
    /// [`reaction_components`](crate::reaction_components)); empty (and not written)
    /// otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub along: Vec<f64>,
}

impl Reaction {
    /// The reaction `force` of `support`, with its components along the `along` directions
    /// when it has some.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_core::Support;
    /// use tensegrity_statics::report::Reaction;
    /// let r = Reaction::of(&Support::along(1, [[0.6, 0.8, 0.0]]), &Vector3::new(3.0, 4.0, 0.0));
    /// assert_eq!((r.node, r.along.len()), (1, 1));
    /// assert!((r.along[0] - 5.0).abs() < 1e-15);
    /// ```
    pub fn of(support: &Support, force: &Vector3<f64>) -> Self {
        let skip = support.fixed.iter().filter(|&&f| f).count();
        Reaction {
            node: support.node,
            force: [force.x, force.y, force.z],
            along: if support.along.is_empty() {
                Vec::new()
            } else {
                crate::reaction_components(support, force).split_off(skip)
            },
        }
    }
}
