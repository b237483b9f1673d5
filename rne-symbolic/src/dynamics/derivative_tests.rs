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

/// The tangent-space partials `(∂f/∂q, ∂f/∂v)` (row-major, NV × NV) of the kernel `f` at `s`
/// against central differences of `f` along each tangent and velocity direction.
fn check_partials(
    d: &SymbolicDynamics,
    f: &[Id],
    (dq, dv): (&[f64], &[f64]),
    s: &State,
    what: &str,
) {
    let (nv, h) = (s.v.len(), 1e-6);
    let scale = dq.iter().chain(dv).fold(1.0f64, |m, x| m.max(x.abs()));
    for c in 0..nv {
        let (plus, minus) = (eval(d, f, &moved(s, c, h)), eval(d, f, &moved(s, c, -h)));
        let (fast, slow) = (eval(d, f, &faster(s, c, h)), eval(d, f, &faster(s, c, -h)));
        for i in 0..nv {
            let fd_q = (plus[i] - minus[i]) / (2.0 * h);
            assert_close(dq[i * nv + c], fd_q, scale, &format!("∂{what}[{i}]/∂q{c}"));
            let fd_v = (fast[i] - slow[i]) / (2.0 * h);
            assert_close(dv[i * nv + c], fd_v, scale, &format!("∂{what}[{i}]/∂v{c}"));
        }
    }
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
    for k in 0..10 {
        let s = state(k);
        let (gq, gv) = (eval(&d, &dq, &s), eval(&d, &dv, &s));
        check_partials(&d, &tau, (&gq, &gv), &s, &format!("τ at state {k}"));
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
        check_partials(&d, &fd, (&gq, &gv), &s, &format!("q̈ at state {k}"));
    }
}

/// The frame behind the fixed joint (`foot`) and a moving one (`hip`): J against finite
/// differences of the placements along each tangent direction, J̇ q̇ against the finite
/// difference of J v along the motion q ⊕ t v.
#[test]
fn frame_jacobians_and_jdot_qd_match_finite_differences_of_the_placements() {
    let mut d = SymbolicDynamics::new(&legged());
    let names: Vec<&str> = d.frames().iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["trunk", "hip", "knee", "foot"]);
    let selected = [3, 1];
    let flatten = |poses: Vec<([[Id; 3]; 3], [Id; 3])>| -> Vec<Id> {
        poses
            .into_iter()
            .flat_map(|(r, p)| r.into_iter().flatten().chain(p))
            .collect()
    };
    let placements = flatten(d.frame_placements(&selected));
    let jacobians: Vec<Id> = d.frame_jacobians(&selected).concat().concat();
    let jdot: Vec<Id> = d.frame_jacobian_dot_qd(&selected).concat();
    let nv = 8;
    let h = 1e-6;
    for k in 0..8 {
        let s = state(k);
        let j = eval(&d, &jacobians, &s);
        for c in 0..nv {
            let plus = eval(&d, &placements, &moved(&s, c, h));
            let minus = eval(&d, &placements, &moved(&s, c, -h));
            let here = eval(&d, &placements, &s);
            for f in 0..2 {
                let at = |x: &[f64], i: usize, l: usize| x[12 * f + 3 * i + l];
                for i in 0..3 {
                    let fd_v = (plus[12 * f + 9 + i] - minus[12 * f + 9 + i]) / (2.0 * h);
                    let got = j[f * 6 * nv + i * nv + c];
                    assert!((got - fd_v).abs() < 1e-7, "J_v[{i}][{c}] of frame {f}");
                }
                // ω = vee(Ṙ Rᵀ).
                let rdot_rt = |a: usize, b: usize| -> f64 {
                    (0..3)
                        .map(|l| (at(&plus, a, l) - at(&minus, a, l)) / (2.0 * h) * at(&here, b, l))
                        .sum()
                };
                let omega = [rdot_rt(2, 1), rdot_rt(0, 2), rdot_rt(1, 0)];
                for i in 0..3 {
                    let got = j[f * 6 * nv + (3 + i) * nv + c];
                    assert!((got - omega[i]).abs() < 1e-7, "J_ω[{i}][{c}] of frame {f}");
                }
            }
        }
        // d/dt (J v) along q ⊕ t v, v constant.
        let along = |t: f64| {
            let mut x = copy(&s);
            for c in 0..nv {
                x = moved(&x, c, t * s.v[c]);
            }
            x
        };
        let jv = |x: &State| -> Vec<f64> {
            let jx = eval(&d, &jacobians, x);
            (0..12)
                .map(|r| (0..nv).map(|c| jx[r * nv + c] * s.v[c]).sum())
                .collect()
        };
        let (plus, minus) = (jv(&along(h)), jv(&along(-h)));
        let got = eval(&d, &jdot, &s);
        for r in 0..12 {
            let fd = (plus[r] - minus[r]) / (2.0 * h);
            assert!(
                (got[r] - fd).abs() < 1e-6,
                "J̇q̇[{r}] state {k}: {} vs {fd}",
                got[r]
            );
        }
    }
}
