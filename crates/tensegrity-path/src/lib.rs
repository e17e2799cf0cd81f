//! Load paths: how an elastic bar-and-string structure deforms under a load that grows, with
//! large displacements, strings that go slack and re-tension, and limit points passed.
//!
//! **Model** ([`model`]). Nodes x, members k from node i to node j with an axial stiffness
//! EA_k and a rest length L₀,k; the tension of member k at length L_k = ‖x_j − x_i‖ is
//!
//! > t_k = EA_k (L_k − L₀,k) / L₀,k,
//!
//! for a string only while L_k > L₀,k (a string is slack at zero force, never compressed).
//! Supports hold a node along given unit directions (any direction, not only x, y, z), or —
//! elastic supports — put a spring of stiffness k along each: the direction stays free, the
//! spring adds k d (d·u) to the resisting force (u the node's displacement from the reference
//! state) and k d dᵀ to the tangent, and its reaction is the spring's force −k d·u. The
//! reference load P (one force per node) is scaled by the load factor λ.
//!
//! **Clustered strings** ([`clusters`]). A cluster runs through several nodes over
//! frictionless pulleys with one tension t = k (L − L₀) (L the sum of its segments' lengths,
//! slack when L ≤ L₀) pulling along every segment; its tangent is k g gᵀ + Σ (t/l_i)(I − e_i
//! e_iᵀ) (g = ∂L/∂x). With pulley friction each segment keeps its own share of the material
//! and slides over a pulley only at the capstan limit t_out = e^{μθ} t_in (load control
//! and the dynamics; module docs of [`clusters`]). Reported tensions give the members, then
//! one per cluster (its largest segment's), and each cluster's segment tensions.
//!
//! **Equilibrium** ([`forces`]). With n_k = (x_j − x_i)/L_k the members' resisting force on
//! node i is R_i = −Σ t_k n_k (member k leaving i), and equilibrium is R(x) = λ P on the
//! free directions; the supports take the rest (the reactions, −(R − λ P) on the held
//! directions).
//!
//! **Tangent stiffness** ([`tangent`]). dR/dx assembles, per taut member,
//!
//! > K_k = (EA_k/L₀,k) n nᵀ + (t_k/L_k)(I − n nᵀ)   (material + geometric),
//!
//! as [[K_k, −K_k], [−K_k, K_k]] on (x_i, x_j); a slack string adds nothing. Its eigenvalues
//! on the free directions are the stability verdict ([`stability`]): all positive, stable; a
//! negative one, unstable (its eigenvector the mode); one near zero, a mechanism. Above
//! [`factor::DENSE_MAX`] free coordinates the tangent is sparse: the verdict is whether its
//! Cholesky factorisation succeeds, and its eigenvalues nearest zero and the mode come from
//! shift-invert subspace iteration with that factorisation ([`factor`]).
//!
//! **Beside the load** ([`model::Drivers`]) λ may drive rest lengths (L₀ + λ ΔL₀) and the
//! motion of supported nodes (λ d), and a dead load D (the bars' weight) acts from λ = 0:
//! equilibrium is R(x, λ) = D + λ P.
//!
//! **Paths.** [`newton`] solves R(x) = λ P at a given λ (load control: [`load_steps()`]);
//! [`arclength`] follows the path (x(s), λ(s)) by its arc length s — a tangent predictor and a
//! Newton corrector on the hyperplane normal to the tangent, in coordinates scaled so that a
//! unit of λ and the linear response to P weigh alike — which passes limit points where λ
//! turns back, locates each (λ to 10⁻⁸ relative, by bisection of the step on the sign of
//! dλ/ds) and reports its mode; bifurcations (an eigenvalue crossing zero without a fold) are
//! located alike, and the path may leave the first one along its mode
//! ([`PathSettings::switch_branch`]).
//!
//! **Dynamics** ([`transient`]). The same model in time: every node a point mass (member
//! masses lumped or consistent, and point masses: [`mass`]), M_r q̈ = Qᵀ(P + W − R − D) on the
//! free coordinates with axial dashpots D, stepped by the explicit RK4 and RK45 of
//! `tensegrity-dynamics` (RK4 refused above its stability limit on the stiffest axial mode)
//! or by Newmark's implicit trapezoidal rule with Newton on (4/h²) M_r + K_T + (2/h) C_T
//! ([`newmark`]); TsgFEM's T-bar dynamics example is reproduced to round-off. Bars may be
//! rigid beside elastic members ([`rigid_bars`]): each keeps its length through the
//! constraint ½(‖x_j − x_i‖² − L²) = 0 and its force Gᵀμ, its mass consistent.

#![warn(missing_docs)]

pub mod actuation;
pub mod arclength;
pub mod clusters;
pub mod dofs;
pub mod error;
pub mod factor;
pub mod forces;
pub mod load_steps;
pub mod mass;
pub mod model;
pub mod newmark;
pub mod newmark_rigid;
pub mod newton;
pub mod point;
pub mod rigid_bars;
pub mod stability;
pub mod tangent;
pub mod transient;
pub mod transient_run;

pub use arclength::{follow, PathSettings};
pub use error::{PathError, Result};
pub use load_steps::load_steps;
pub use mass::{MassDistribution, Masses};
pub use model::{ElasticCluster, ElasticMember, ElasticModel, MemberKind, Support};
pub use point::{Event, PathPoint, PathReport};
pub use transient::ElasticDynamics;
