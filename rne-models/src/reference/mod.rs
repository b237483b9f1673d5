//! The independent numeric reference: spatial-vector RNEA, CRBA and ABA on nalgebra.
