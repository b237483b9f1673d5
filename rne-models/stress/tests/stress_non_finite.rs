//! Case 8 of `rne stress`: NaN and infinite inputs give NaN (or ±∞) outputs, exactly in the
//! outputs that depend on the bad entry, and never a panic or a hang — in every kernel.

use rne_interpreted::{Interpreted, RuntimeModel};
use rne_models::BUILTIN_ROBOTS;
use rne_sim::{Dopri5, GaussLegendre, Rk4, SimError};
use rne_stress::cases::non_finite::{check, check_builtin, integrate_from_nan};
use rne_stress::random_robot;
use rne_stress::states::generator;

/// Bound: zero violations and zero panics over every kernel of every built-in robot
/// (compiled), every input entry, NaN, +∞ and −∞; at least one output depends on each input.
#[test]
fn every_builtin_kernel_propagates_nan_and_infinity() {
    for robot in BUILTIN_ROBOTS {
        let c = check_builtin(robot, 1).unwrap();
        assert_eq!(c.panics, 0, "{}", c.robot);
        assert_eq!(c.violation_count, 0, "{}: {:#?}", c.robot, c.violations);
        assert!(c.dependent > c.calls, "{}: {c:?}", c.robot);
    }
}

/// The same for the programs of a random robot with prismatic joints, evaluated at run time.
#[test]
fn graph_evaluation_propagates_nan_and_infinity() {
    let chain = random_robot(&mut generator(11), 5);
    let model = chain.model().unwrap();
    let programs = Interpreted::new(&model);
    let runtime = RuntimeModel::<5>::interpreted(&programs).unwrap();
    let c = check("random-5", &runtime, &programs, 1).unwrap();
    assert_eq!((c.panics, c.violation_count), (0, 0), "{:#?}", c.violations);
}

/// The integrators stop with an error at a non-finite state instead of looping.
#[test]
fn integrators_stop_on_non_finite_states() {
    let non_finite = |r: Result<(), SimError>| matches!(r, Err(SimError::NonFinite { .. }));
    assert!(non_finite(integrate_from_nan(&Rk4::new(1e-3))));
    assert!(non_finite(integrate_from_nan(&Dopri5::new(1e-10, 1e-12))));
    assert!(integrate_from_nan(&GaussLegendre::new(1e-3)).is_err());
}
