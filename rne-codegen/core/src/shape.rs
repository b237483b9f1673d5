//! The Rust type a kernel returns and how its flat outputs fill it: scalars, arrays of the
//! module's sizes (NV, NF, NP, NB) and tuples, nested.

use proc_macro2::TokenStream;

use crate::kernel::{Dims, Kernel, Shape};

/// A return type, as a tree.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Layout {
    /// One scalar.
    Scalar,
    /// `[element; N]`, N named by a module constant (`NV`, `NF`, ...) or a literal size.
    Array(Box<Layout>, Size),
    /// `(a, b, ...)`.
    Tuple(Vec<Layout>),
}

/// The length of an array.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct Size {
    /// The module constant naming it, or `None` for a literal.
    pub name: Option<&'static str>,
    /// Its value in this module.
    pub value: usize,
}

impl Size {
    fn named(name: &'static str, value: usize) -> Size {
        Size {
            name: Some(name),
            value,
        }
    }

    fn literal(value: usize) -> Size {
        Size { name: None, value }
    }
}

impl Layout {
    /// The layout of `kernel`'s result in a module of sizes `dims`.
    pub fn of(kernel: Kernel, dims: Dims) -> Layout {
        let nv = Size::named("NV", dims.nv);
        let array = |element: Layout, size: Size| Layout::Array(Box::new(element), size);
        let vector = |size: Size| array(Layout::Scalar, size);
        let matrix = |rows: Size, columns: Size| array(vector(columns), rows);
        match kernel.shape() {
            Shape::Scalar => Layout::Scalar,
            Shape::Vector => vector(nv),
            Shape::Matrix => matrix(nv, nv),
            Shape::Matrices(count) => Layout::Tuple(vec![matrix(nv, nv); count]),
            Shape::Placements => {
                let three = Size::literal(3);
                let placement = Layout::Tuple(vec![matrix(three, three), vector(three)]);
                array(placement, Size::named("NF", dims.nf))
            }
            Shape::FrameMatrices => array(matrix(Size::literal(6), nv), Size::named("NF", dims.nf)),
            Shape::FrameVectors => matrix(Size::named("NF", dims.nf), Size::literal(6)),
            Shape::Regressor => matrix(nv, Size::named("NP", dims.np)),
            Shape::BaseRegressor => matrix(nv, Size::named("NB", dims.nb)),
            Shape::BaseVector => vector(Size::named("NB", dims.nb)),
            other => unreachable!("no layout for the shape {other:?}"),
        }
    }

    /// Number of scalars.
    pub fn len(&self) -> usize {
        match self {
            Layout::Scalar => 1,
            Layout::Array(element, size) => element.len() * size.value,
            Layout::Tuple(parts) => parts.iter().map(Layout::len).sum(),
        }
    }

    /// The Rust type, with scalar `t` ([`Layout::type_text`] lexed).
    pub fn type_tokens(&self, t: &TokenStream) -> TokenStream {
        self.type_text(&t.to_string())
            .parse()
            .expect("a type is Rust")
    }

    /// The Rust type with scalar `t`, as source text.
    pub fn type_text(&self, t: &str) -> String {
        match self {
            Layout::Scalar => t.to_owned(),
            Layout::Array(element, size) => {
                let length = match size.name {
                    Some(name) => name.to_owned(),
                    None => size.value.to_string(),
                };
                format!("[{}; {length}]", element.type_text(t))
            }
            Layout::Tuple(parts) => {
                let parts: Vec<String> = parts.iter().map(|p| p.type_text(t)).collect();
                format!("({})", parts.join(", "))
            }
        }
    }

    /// Each scalar's place in the value as the index suffix of an expression of this type
    /// (`[2][3]`, `.1[0]`; empty for a scalar), in the order of [`Layout::write_value`].
    pub fn places(&self) -> Vec<String> {
        match self {
            Layout::Scalar => vec![String::new()],
            Layout::Array(element, size) => {
                let inner = element.places();
                (0..size.value)
                    .flat_map(|k| inner.iter().map(move |p| format!("[{k}]{p}")))
                    .collect()
            }
            Layout::Tuple(parts) => parts
                .iter()
                .enumerate()
                .flat_map(|(k, part)| part.places().into_iter().map(move |p| format!(".{k}{p}")))
                .collect(),
        }
    }

    /// The value built from `scalars` (Rust expressions), taken in order (row-major, tuple
    /// parts in turn), appended to `out` as source text.
    pub fn write_value(&self, scalars: &mut impl Iterator<Item = String>, out: &mut String) {
        match self {
            Layout::Scalar => out.push_str(&scalars.next().expect("one scalar per output")),
            Layout::Array(element, size) => {
                out.push('[');
                for k in 0..size.value {
                    if k > 0 {
                        out.push_str(", ");
                    }
                    element.write_value(scalars, out);
                }
                out.push(']');
            }
            Layout::Tuple(parts) => {
                out.push('(');
                for (k, part) in parts.iter().enumerate() {
                    if k > 0 {
                        out.push_str(", ");
                    }
                    part.write_value(scalars, out);
                }
                out.push(')');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    const DIMS: Dims = Dims {
        nv: 2,
        nf: 3,
        np: 20,
        nb: 5,
    };

    fn type_of(kernel: Kernel) -> String {
        Layout::of(kernel, DIMS)
            .type_tokens(&quote!(f64))
            .to_string()
            .replace(' ', "")
    }

    #[test]
    fn return_types_are_those_of_design_section_4() {
        assert_eq!(type_of(Kernel::KineticEnergy), "f64");
        assert_eq!(type_of(Kernel::InverseDynamics), "[f64;NV]");
        assert_eq!(type_of(Kernel::MassMatrix), "[[f64;NV];NV]");
        assert_eq!(
            type_of(Kernel::InverseDynamicsDerivatives),
            "([[f64;NV];NV],[[f64;NV];NV])"
        );
        assert_eq!(
            type_of(Kernel::FramePlacements),
            "[([[f64;3];3],[f64;3]);NF]"
        );
        assert_eq!(type_of(Kernel::FrameJacobians), "[[[f64;NV];6];NF]");
        assert_eq!(type_of(Kernel::FrameJacobianDotQd), "[[f64;6];NF]");
        assert_eq!(type_of(Kernel::Regressor), "[[f64;NP];NV]");
        assert_eq!(type_of(Kernel::BaseRegressor), "[[f64;NB];NV]");
        assert_eq!(type_of(Kernel::BaseParameters), "[f64;NB]");
    }

    #[test]
    fn lengths_count_every_scalar() {
        assert_eq!(
            Layout::of(Kernel::ForwardDynamicsDerivatives, DIMS).len(),
            12
        );
        assert_eq!(Layout::of(Kernel::FramePlacements, DIMS).len(), 36);
        assert_eq!(Layout::of(Kernel::FrameJacobians, DIMS).len(), 36);
        assert_eq!(Layout::of(Kernel::Regressor, DIMS).len(), 40);
    }

    #[test]
    fn places_follow_the_order_values_are_written_in() {
        let layout = Layout::of(Kernel::InverseDynamicsDerivatives, DIMS);
        assert_eq!(
            layout.places(),
            [
                ".0[0][0]", ".0[0][1]", ".0[1][0]", ".0[1][1]", ".1[0][0]", ".1[0][1]", ".1[1][0]",
                ".1[1][1]"
            ]
        );
        assert_eq!(Layout::Scalar.places(), [""]);
        let placements = Layout::of(Kernel::FramePlacements, DIMS);
        assert_eq!(placements.places().len(), placements.len());
        assert_eq!(placements.places()[12], "[1].0[0][0]");
    }

    #[test]
    fn values_fill_row_major_and_tuples_in_turn() {
        let layout = Layout::of(Kernel::InverseDynamicsDerivatives, DIMS);
        let mut scalars = (0..8).map(|i| i.to_string());
        let mut value = String::new();
        layout.write_value(&mut scalars, &mut value);
        let value = value.replace(' ', "");
        assert_eq!(value, "([[0,1],[2,3]],[[4,5],[6,7]])");
        assert!(scalars.next().is_none());
    }
}
