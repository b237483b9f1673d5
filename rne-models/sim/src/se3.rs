//! The group SE(3) of a free-flyer base, as the variational integrator needs it: the
//! exponential of a body twist, the coadjoint actions on momenta, and the transposed
//! differential of the exponential.
//!
//! Conventions are Pinocchio's (docs/design.md §8): a twist ξ = [v; ω] (linear first, body frame),
//! a momentum or wrench μ = [f; n] (force first, moment about the frame's origin, body axes), a
//! quaternion [x, y, z, w]. With ad_ξ η = [ω × η_v + v × η_ω; ω × η_ω] (the bracket of se(3)),
//! the series and identities are those of Iserles, Munthe-Kaas, Nørsett and Zanna, "Lie-group
//! methods", Acta Numerica 9 (2000), section 2.

/// A vector of ℝ³.
pub(crate) type Vec3 = [f64; 3];
/// A body twist [v; ω] or a momentum [f; n].
pub(crate) type Six = [f64; 6];

/// a × b.
pub(crate) fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// R x.
pub(crate) fn rotate(r: &[[f64; 3]; 3], x: &Vec3) -> Vec3 {
    std::array::from_fn(|i| r[i][0] * x[0] + r[i][1] * x[1] + r[i][2] * x[2])
}

/// Rᵀ x.
pub(crate) fn rotate_back(r: &[[f64; 3]; 3], x: &Vec3) -> Vec3 {
    std::array::from_fn(|j| r[0][j] * x[0] + r[1][j] * x[1] + r[2][j] * x[2])
}

/// The rotation matrix of a unit quaternion [x, y, z, w].
pub(crate) fn rotation(q: &[f64; 4]) -> [[f64; 3]; 3] {
    let [x, y, z, w] = *q;
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - z * w),
            2.0 * (x * z + y * w),
        ],
        [
            2.0 * (x * y + z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - x * w),
        ],
        [
            2.0 * (x * z - y * w),
            2.0 * (y * z + x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// The Hamilton product a ⊗ b of quaternions [x, y, z, w], so that R(a ⊗ b) = R(a) R(b).
pub(crate) fn quaternion_product(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    let (av, aw) = ([a[0], a[1], a[2]], a[3]);
    let (bv, bw) = ([b[0], b[1], b[2]], b[3]);
    let c = cross(&av, &bv);
    [
        aw * bv[0] + bw * av[0] + c[0],
        aw * bv[1] + bw * av[1] + c[1],
        aw * bv[2] + bw * av[2] + c[2],
        aw * bw - (av[0] * bv[0] + av[1] * bv[1] + av[2] * bv[2]),
    ]
}

/// A rigid displacement x ↦ R x + p: the base's motion over one step, in the base frame it
/// starts from.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Displacement {
    /// The rotation R as a unit quaternion [x, y, z, w].
    pub quaternion: [f64; 4],
    /// R as a matrix.
    pub rotation: [[f64; 3]; 3],
    /// The translation p.
    pub translation: Vec3,
}

/// exp(ξ) for a twist ξ = [v; ω] of se(3): R = Exp(ω) (Rodrigues, as the quaternion
/// [sin(θ/2) ω/θ, cos(θ/2)], θ = |ω|) and p = V(ω) v with
/// V(ω) = 1 + (1 − cos θ)/θ² ω× + (θ − sin θ)/θ³ ω×² (Pinocchio's `exp6`; Murray, Li and
/// Sastry, *A Mathematical Introduction to Robotic Manipulation*, (2.36)). Below θ = 1e-4 the
/// coefficients are their Taylor polynomials, exact to rounding there.
pub(crate) fn exp(xi: &Six) -> Displacement {
    let v = [xi[0], xi[1], xi[2]];
    let w = [xi[3], xi[4], xi[5]];
    let theta2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    let theta = theta2.sqrt();
    let (a, b, half_sinc) = if theta < 1e-4 {
        (
            0.5 - theta2 / 24.0,
            1.0 / 6.0 - theta2 / 120.0,
            0.5 - theta2 / 48.0,
        )
    } else {
        (
            (1.0 - theta.cos()) / theta2,
            (theta - theta.sin()) / (theta2 * theta),
            (0.5 * theta).sin() / theta,
        )
    };
    let wv = cross(&w, &v);
    let wwv = cross(&w, &wv);
    let translation = std::array::from_fn(|i| v[i] + a * wv[i] + b * wwv[i]);
    let quaternion = [
        half_sinc * w[0],
        half_sinc * w[1],
        half_sinc * w[2],
        (0.5 * theta).cos(),
    ];
    Displacement {
        quaternion,
        rotation: rotation(&quaternion),
        translation,
    }
}

/// Ad_gᵀ μ for g = (R, p): the momentum μ = [f; n] (at the origin of the frame g starts from,
/// in its axes) seen at the displaced frame, [Rᵀ f; Rᵀ (n − p × f)].
pub(crate) fn co_adjoint(g: &Displacement, mu: &Six) -> Six {
    let f = [mu[0], mu[1], mu[2]];
    let pf = cross(&g.translation, &f);
    let n = [mu[3] - pf[0], mu[4] - pf[1], mu[5] - pf[2]];
    let (f, n) = (rotate_back(&g.rotation, &f), rotate_back(&g.rotation, &n));
    [f[0], f[1], f[2], n[0], n[1], n[2]]
}

/// ad_ξᵀ μ = [f × ω; f × v + n × ω], the transpose of the bracket ad_ξ η = [ξ, η]. The
/// Euler–Poincaré equation of a free body reads μ̇ = ad_ξᵀ μ in these conventions.
pub(crate) fn co_ad(xi: &Six, mu: &Six) -> Six {
    let (v, w) = ([xi[0], xi[1], xi[2]], [xi[3], xi[4], xi[5]]);
    let (f, n) = ([mu[0], mu[1], mu[2]], [mu[3], mu[4], mu[5]]);
    let fw = cross(&f, &w);
    let fv = cross(&f, &v);
    let nw = cross(&n, &w);
    [
        fw[0],
        fw[1],
        fw[2],
        fv[0] + nw[0],
        fv[1] + nw[1],
        fv[2] + nw[2],
    ]
}

/// Terms of the series of [`dexp_transpose`] beyond which it stops regardless.
const SERIES_TERMS: u32 = 60;

/// dexp_Xᵀ μ = Σₖ (ad_Xᵀ)ᵏ μ / (k + 1)!, where dexp_X = (e^{ad_X} − 1)/ad_X is the right-trivialised
/// differential of exp: d/dε exp(X + εY) = dexp_X(Y) exp(X) (Iserles et al. 2000, (2.42)).
///
/// The series is entire; it is summed until a term no longer changes the sum (at most
/// [`SERIES_TERMS`] terms, which reach rounding for |X| up to about 10, far beyond one step's
/// rotation).
pub(crate) fn dexp_transpose(x: &Six, mu: &Six) -> Six {
    let mut sum = *mu;
    let mut term = *mu;
    for k in 1..SERIES_TERMS {
        let next = co_ad(x, &term);
        term = std::array::from_fn(|i| next[i] / f64::from(k + 1));
        let before = sum;
        for (s, t) in sum.iter_mut().zip(&term) {
            *s += t;
        }
        if sum == before {
            break;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    /// exp of a pure rotation about z by θ is that rotation; the quaternion is unit; a twist
    /// with ω ∥ v is a screw whose translation is v (V(ω) v = v when ω × v = 0).
    #[test]
    fn exp_of_known_twists() {
        let theta: f64 = 0.7;
        let g = exp(&[0.0, 0.0, 0.0, 0.0, 0.0, theta]);
        let (c, s) = (theta.cos(), theta.sin());
        let expected = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        for (row, e) in g.rotation.iter().zip(&expected) {
            assert!(close(row, e, 1e-15), "{:?}", g.rotation);
        }
        let norm: f64 = g.quaternion.iter().map(|x| x * x).sum();
        assert!((norm - 1.0).abs() < 1e-15);
        let screw = exp(&[0.0, 0.0, 2.0, 0.0, 0.0, theta]);
        assert!(close(&screw.translation, &[0.0, 0.0, 2.0], 1e-15));
        // A quarter turn about z while moving along x at unit speed: the arc of radius 2/π.
        let quarter = exp(&[1.0, 0.0, 0.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        let r = 2.0 / std::f64::consts::PI;
        assert!(close(&quarter.translation, &[r, r, 0.0], 1e-15));
        // The Taylor branch just below the switch agrees with the closed form (whose
        // cancellation leaves about 1e-8 relative error in its coefficients there).
        let (v, w) = ([0.3, -0.2, 0.1], [0.99e-4 * 0.6, 0.99e-4 * 0.8, 0.0]);
        let small = exp(&[v[0], v[1], v[2], w[0], w[1], w[2]]);
        let theta: f64 = 0.99e-4;
        let a = (1.0 - theta.cos()) / (theta * theta);
        let b = (theta - theta.sin()) / theta.powi(3);
        let (wv, wwv) = (cross(&w, &v), cross(&w, &cross(&w, &v)));
        let closed: Vec<f64> = (0..3).map(|i| v[i] + a * wv[i] + b * wwv[i]).collect();
        assert!(close(&small.translation, &closed, 1e-12));
    }

    /// Quaternion products compose rotations: R(a ⊗ b) = R(a) R(b).
    #[test]
    fn quaternion_product_composes_rotations() {
        let a = exp(&[0.0, 0.0, 0.0, 0.3, -0.5, 0.2]).quaternion;
        let b = exp(&[0.0, 0.0, 0.0, -0.1, 0.4, 0.9]).quaternion;
        let (ra, rb) = (rotation(&a), rotation(&b));
        let rab = rotation(&quaternion_product(&a, &b));
        for i in 0..3 {
            for j in 0..3 {
                let m: f64 = (0..3).map(|k| ra[i][k] * rb[k][j]).sum();
                assert!((m - rab[i][j]).abs() < 1e-15);
            }
        }
    }

    /// The differential of exp, by central differences of exp(X + εY) exp(−X) at ε = 0
    /// (whose rotation is 1 + ε ω(Y')× and translation ε v(Y') for Y' = dexp_X Y): the pairing
    /// ⟨μ, dexp_X Y⟩ equals ⟨dexp_Xᵀ μ, Y⟩.
    #[test]
    fn dexp_transpose_is_the_transposed_differential_of_exp() {
        let x = [0.4, -0.3, 0.8, 0.9, -0.6, 0.5];
        let y = [0.2, 0.7, -0.1, -0.3, 0.25, 0.6];
        let mu = [1.0, -2.0, 0.5, 0.3, 0.8, -1.2];
        let moved = |e: f64| {
            let a = exp(&std::array::from_fn(|i| x[i] + e * y[i]));
            let inverse = exp(&x.map(|c| -c));
            // (R_a, p_a) ∘ (R_b, p_b) = (R_a R_b, R_a p_b + p_a).
            let r: [[f64; 3]; 3] = std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    (0..3)
                        .map(|k| a.rotation[i][k] * inverse.rotation[k][j])
                        .sum()
                })
            });
            let p = rotate(&a.rotation, &inverse.translation);
            let p: Vec3 = std::array::from_fn(|i| p[i] + a.translation[i]);
            (r, p)
        };
        let e = 1e-6;
        let ((rp, pp), (rm, pm)) = (moved(e), moved(-e));
        let d = |i: usize, j: usize| (rp[i][j] - rm[i][j]) / (2.0 * e);
        let twist = [
            (pp[0] - pm[0]) / (2.0 * e),
            (pp[1] - pm[1]) / (2.0 * e),
            (pp[2] - pm[2]) / (2.0 * e),
            d(2, 1),
            d(0, 2),
            d(1, 0),
        ];
        let lhs: f64 = mu.iter().zip(&twist).map(|(a, b)| a * b).sum();
        let dt = dexp_transpose(&x, &mu);
        let rhs: f64 = dt.iter().zip(&y).map(|(a, b)| a * b).sum();
        assert!((lhs - rhs).abs() < 1e-8, "{lhs} vs {rhs}");
    }

    /// The identity the integrator's momentum transport rests on: dexp_{−X} = Ad_{exp(−X)} dexp_X,
    /// i.e. dexp_{−X}ᵀ = dexp_Xᵀ Ad_{exp(−X)}ᵀ, checked on a covector.
    #[test]
    fn dexp_of_minus_x_is_dexp_of_x_seen_from_the_end() {
        let x = [0.4, -0.3, 0.8, 0.9, -0.6, 0.5];
        let mu = [1.0, -2.0, 0.5, 0.3, 0.8, -1.2];
        let minus = x.map(|c| -c);
        let lhs = dexp_transpose(&minus, &mu);
        let rhs = dexp_transpose(&x, &co_adjoint(&exp(&minus), &mu));
        assert!(close(&lhs, &rhs, 1e-14), "{lhs:?} vs {rhs:?}");
    }
}
