//! Simulation: integrators, controllers and the thesis's chapter 6 experiments.
