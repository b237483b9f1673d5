//! Expression graphs evaluate in the runtime's double-double scalar to about 32 digits.

use rne_symbolic::{DoubleDouble, ExprGraph, Real, Symbol, SymbolTable};

#[test]
fn sin_squared_plus_cos_squared_is_one_to_1e_31_in_double_double() {
    let mut g = ExprGraph::new(SymbolTable::with_joints(["q1"]));
    let id = g
        .parse_sexpr("(- (+ (* (sin q1) (sin q1)) (* (cos q1) (cos q1))) 1)")
        .unwrap();
    let q1 = DoubleDouble::from_parts(0.7, 1e-18);
    let defect = g.eval::<DoubleDouble>(&[id], |_: Symbol| q1)[0];
    assert!(defect.abs().to_f64() <= 1e-31, "{defect}");
    assert_eq!(
        <DoubleDouble as Real>::sin(DoubleDouble::ZERO),
        DoubleDouble::ZERO
    );
}
