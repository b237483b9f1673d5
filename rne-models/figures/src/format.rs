//! The number formats of every report: errors in scientific notation and in ulps.

/// An error in scientific notation with two significant digits: `1.2e-16`; `0`, `NaN`, `inf`.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.is_finite() {
        format!("{x:.1e}")
    } else {
        format!("{x}")
    }
}

/// An error in ulps: two decimals below 10, none below 10⁴, scientific above; `NaN`, `inf`.
pub fn ulps(u: f64) -> String {
    if !u.is_finite() {
        format!("{u}")
    } else if u < 10.0 {
        format!("{u:.2}")
    } else if u < 1e4 {
        format!("{u:.0}")
    } else {
        format!("{u:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each magnitude gets its format; zero and non-finite values are spelled out.
    #[test]
    fn formats_by_magnitude() {
        assert_eq!(sci(1.234e-16), "1.2e-16");
        assert_eq!(sci(0.0), "0");
        assert_eq!(sci(f64::NAN), "NaN");
        assert_eq!(sci(f64::INFINITY), "inf");
        assert_eq!(ulps(0.514), "0.51");
        assert_eq!(ulps(123.4), "123");
        assert_eq!(ulps(2.5e4), "2.5e4");
        assert_eq!(ulps(f64::NAN), "NaN");
    }
}
