//! The symbolic derivatives against central finite differences of the kernels they
//! differentiate, on the floating legged model (tangent-space base columns, a revolute and a
//! prismatic joint) and on the fixed-base planar elbow.

use super::floating_tests::{eval, legged, state, State};
use super::SymbolicDynamics;
use crate::expr::Id;

/// `s` moved by `h` along tangent direction k of the configuration (`q ⊕ h e_k`): the base
/// position by `R h e_k` (k < 3), the orientation by `R Exp(h e_{k−3})` (3 ≤ k < 6), a joint
/// by `h`.
fn moved(s: &State, k: usize, h: f64) -> State {
    let mut out = copy(s);
    let r = super::floating_tests::rotation(s);
    match k {
        0..=2 => {
            for i in 0..3 {
                out.q[i] += r[i][k] * h;
            }
        }
        3..=5 => {
            // quat ⊗ (sin(h/2) e_a, cos(h/2)).
            let [x, y, z, w] = [s.q[3], s.q[4], s.q[5], s.q[6]];
            let (sn, cs) = (h / 2.0).sin_cos();
            let mut e = [0.0; 3];
            e[k - 3] = sn;
            let [ex, ey, ez] = e;
            out.q[3] = w * ex + x * cs + y * ez - z * ey;
            out.q[4] = w * ey + y * cs + z * ex - x * ez;
            out.q[5] = w * ez + z * cs + x * ey - y * ex;
            out.q[6] = w * cs - x * ex - y * ey - z * ez;
        }
        _ => out.q[k + 1] += h,
    }
    out
}

fn copy(s: &State) -> State {
    State {
        q: s.q.clone(),
        v: s.v.clone(),
        a: s.a.clone(),
        u: s.u.clone(),
    }
}

/// `s` with velocity entry k moved by `h`.
fn faster(s: &State, k: usize, h: f64) -> State {
    let mut out = copy(s);
    out.v[k] += h;
    out
}

fn assert_close(got: f64, expected: f64, scale: f64, what: &str) {
    assert!(
        (got - expected).abs() <= 1e-6 * scale,
        "{what}: {got} vs finite difference {expected}"
    );
}

#[test]
fn inverse_dynamics_derivatives_match_finite_differences_in_the_tangent_space() {
    let mut d = SymbolicDynamics::new(&legged());
    let tau = d.inverse_dynamics();
    let (dq, dv) = d.inverse_dynamics_derivatives();
    let (dq, dv): (Vec<Id>, Vec<Id>) = (dq.concat(), dv.concat());
    let nv = 8;
    let h = 1e-6;
    for k in 0..10 {
        let s = state(k);
        let (gq, gv) = (eval(&d, &dq, &s), eval(&d, &dv, &s));
        let scale = gq.iter().chain(&gv).fold(1.0f64, |m, x| m.max(x.abs()));
        for c in 0..nv {
            let plus = eval(&d, &tau, &moved(&s, c, h));
            let minus = eval(&d, &tau, &moved(&s, c, -h));
            let tp = eval(&d, &tau, &faster(&s, c, h));
            let tm = eval(&d, &tau, &faster(&s, c, -h));
            for i in 0..nv {
                let fd_q = (plus[i] - minus[i]) / (2.0 * h);
                assert_close(
                    gq[i * nv + c],
                    fd_q,
                    scale,
                    &format!("dτ{i}/dq{c} state {k}"),
                );
                let fd_v = (tp[i] - tm[i]) / (2.0 * h);
                assert_close(
                    gv[i * nv + c],
                    fd_v,
                    scale,
                    &format!("dτ{i}/dv{c} state {k}"),
                );
            }
        }
    }
}

#[test]
fn forward_dynamics_derivatives_match_finite_differences_and_minv_inverts_m() {
    let mut d = SymbolicDynamics::new(&legged());
    let fd = d.forward_dynamics();
    let (dq, dv, minv) = d.forward_dynamics_derivatives();
    let (dq, dv, minv): (Vec<Id>, Vec<Id>, Vec<Id>) = (dq.concat(), dv.concat(), minv.concat());
    let m: Vec<Id> = d.mass_matrix().concat();
    let nv = 8;
    let h = 1e-6;
    for k in 0..10 {
        let s = state(k);
        let (gq, gv) = (eval(&d, &dq, &s), eval(&d, &dv, &s));
        let (inv, mm) = (eval(&d, &minv, &s), eval(&d, &m, &s));
        for i in 0..nv {
            for j in 0..nv {
                let product: f64 = (0..nv).map(|l| inv[i * nv + l] * mm[l * nv + j]).sum();
                let identity = if i == j { 1.0 } else { 0.0 };
                assert!((product - identity).abs() < 1e-12, "M⁻¹ M at ({i}, {j})");
            }
        }
        let scale = gq.iter().chain(&gv).fold(1.0f64, |m, x| m.max(x.abs()));
        for c in 0..nv {
            let plus = eval(&d, &fd, &moved(&s, c, h));
            let minus = eval(&d, &fd, &moved(&s, c, -h));
            let ap = eval(&d, &fd, &faster(&s, c, h));
            let am = eval(&d, &fd, &faster(&s, c, -h));
            for i in 0..nv {
                let fd_q = (plus[i] - minus[i]) / (2.0 * h);
                assert_close(
                    gq[i * nv + c],
                    fd_q,
                    scale,
                    &format!("dq̈{i}/dq{c} state {k}"),
                );
                let fd_v = (ap[i] - am[i]) / (2.0 * h);
                assert_close(
                    gv[i * nv + c],
                    fd_v,
                    scale,
                    &format!("dq̈{i}/dv{c} state {k}"),
                );
            }
        }
    }
}
