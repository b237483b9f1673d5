"""Identification from Python as `rne identify` does it: an excitation with simulated noisy
torques, the base parameters estimated from it near the model's, and a prediction on a fresh
record within the noise."""
import numpy as np

import rne


def test_excite_identify_validate():
    # The planar elbow's file has joint friction, which identification always models (as
    # `rne identify` does): the torques it simulates are those of the model with friction.
    model = rne.load("planar-elbow", friction=True)
    data = rne.excitation(model, iterations=20, criterion_states=50, noise=0.01, seed=1)
    n = len(data.t)
    assert data.q.shape == (n, model.nq) and data.tau.shape == (n, model.nv)
    assert np.all(np.abs(data.q) <= 1.5 + 1e-9) and data.condition_number > 1
    # The simulated torques are the model's inverse dynamics plus 1 % noise.
    clean = model.rnea(data.q, data.v, data.a)
    assert 0 < np.sqrt(np.mean((data.tau - clean) ** 2)) < 0.05 * np.sqrt(np.mean(clean**2))
    result = rne.identify(model, data.q, data.v, data.a, data.tau)
    assert len(result.values) == data.base_parameters == len(result.names)
    # Every estimate within five of its standard deviations of the model's value.
    assert np.all(np.abs(result.values - result.model) <= 5 * result.std + 1e-9)
    assert result.weighted and result.condition_number > 1
    fresh = rne.excitation(model, iterations=20, criterion_states=50, noise=0.01, seed=2)
    check = rne.validate(model, result, fresh.q, fresh.v, fresh.a, fresh.tau)
    assert check.relative_rms < 0.03 and check.joints.shape == (model.nv,)
    exact = rne.validate(model, result.model, fresh.q, fresh.v, fresh.a)
    np.testing.assert_allclose(exact.tau, model.rnea(fresh.q, fresh.v, fresh.a), atol=1e-9)
    assert exact.relative_rms is None


def test_unweighted_and_friction():
    model = rne.load("planar-elbow")
    data = rne.excitation(model, iterations=10, criterion_states=40, noise=0.0, friction=True)
    result = rne.identify(model, data.q, data.v, data.a, data.tau, weighted=False, friction=True)
    assert not result.weighted and result.friction
    np.testing.assert_allclose(result.values, result.model, rtol=1e-6, atol=1e-6)
