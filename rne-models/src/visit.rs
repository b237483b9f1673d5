//! Code written once over [`Dynamics`], run on a robot chosen at run time.

use rne_codegen::Dynamics;

/// A computation generic over a robot's dynamics: [`BuiltinRobot::visit`] calls it with the
/// robot's generated `Model`, so that the command line, the benchmarks and the checks pick a
/// robot by name and still call its kernels statically dispatched.
///
/// The built-in robots have fixed bases, so NQ = NV = N; they compute in `f64`.
///
/// ```
/// use rne_codegen::Dynamics;
/// use rne_models::{builtin, Visitor};
///
/// /// The number of joints and the gravity torques at q = 0.
/// struct HoldingTorques;
///
/// impl Visitor for HoldingTorques {
///     type Output = (usize, Option<Vec<f64>>);
///     fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output {
///         (N, model.gravity_torques(&[0.0; N]).map(|g| g.to_vec()))
///     }
/// }
///
/// let (n, g) = builtin("planar-elbow").unwrap().visit(HoldingTorques);
/// assert_eq!(n, 2);
/// assert!(g.unwrap()[0] != 0.0);
/// ```
///
/// [`BuiltinRobot::visit`]: crate::BuiltinRobot::visit
pub trait Visitor {
    /// What the computation returns.
    type Output;

    /// Runs the computation on `model`, a robot with N joints.
    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output;
}
