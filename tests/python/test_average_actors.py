"""average_actors: the mean of compatible actors' weights, and a clear refusal of incompatible ones."""

import json

import numpy as np
import pytest

from guidewire_nav.average_actors import average_actors, main
from guidewire_nav.export_actor import FORMAT


def _actor(seed: int, sizes=(11, 4, 1), layout="guidewire-nav/obs/1") -> dict:
    rng = np.random.default_rng(seed)
    layers = []
    for i, (n_in, n_out) in enumerate(zip(sizes[:-1], sizes[1:])):
        layers.append({"shape": [n_out, n_in], "weight": rng.normal(size=n_out * n_in).tolist(),
                       "bias": rng.normal(size=n_out).tolist(),
                       "activation": "identity" if i == len(sizes) - 2 else "relu"})
    return {"format": FORMAT, "obs_size": sizes[0], "action_size": sizes[-1], "obs_layout": layout,
            "obs_normalization": None, "layers": layers,
            "output": {"squash": "tanh", "low": [-1.0], "high": [1.0]},
            "training_settings": {"seed": seed}, "git_commit": None, "source": {"algorithm": "SB3 SAC"}}


def test_every_weight_is_the_mean_of_the_inputs():
    a, b, c = _actor(0), _actor(1), _actor(2)
    soup = average_actors([a, b, c], ["a", "b", "c"])
    for i, layer in enumerate(soup["layers"]):
        for key in ("weight", "bias"):
            expected = (np.array(a["layers"][i][key]) + np.array(b["layers"][i][key]) + np.array(c["layers"][i][key])) / 3
            np.testing.assert_allclose(layer[key], expected, rtol=0, atol=1e-15)
        assert layer["shape"] == a["layers"][i]["shape"] and layer["activation"] == a["layers"][i]["activation"]
    assert soup["source"]["averaged_from"] == ["a", "b", "c"]
    assert soup["obs_layout"] == a["obs_layout"] and soup["output"] == a["output"]
    # The inputs are left as they were.
    assert a["layers"][0]["weight"] != soup["layers"][0]["weight"]


@pytest.mark.parametrize("other, named", [
    (_actor(1, sizes=(11, 5, 1)), "layers"),
    (_actor(1, layout="guidewire-nav/obs/3"), "obs_layout"),
])
def test_incompatible_actors_are_refused_naming_the_difference(other, named):
    with pytest.raises(ValueError, match=f"second: {named}"):
        average_actors([_actor(0), other], ["first", "second"])


def test_one_actor_or_a_foreign_format_is_refused():
    with pytest.raises(ValueError, match="at least two"):
        average_actors([_actor(0)])
    foreign = dict(_actor(0), format="something/else")
    with pytest.raises(ValueError, match="format"):
        average_actors([foreign, _actor(1)])


def test_cli_writes_the_soup_and_nothing_on_error(tmp_path, capsys):
    paths = []
    for seed in (0, 1):
        paths.append(tmp_path / f"a{seed}.json")
        paths[-1].write_text(json.dumps(_actor(seed)))
    out = tmp_path / "soup.json"
    assert main([str(out), *map(str, paths)]) == 0
    soup = json.loads(out.read_text())
    np.testing.assert_allclose(soup["layers"][1]["bias"],
                               (np.array(_actor(0)["layers"][1]["bias"]) + _actor(1)["layers"][1]["bias"]) / 2)
    assert all("sha256" in s for s in soup["source"]["averaged_from"])

    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(_actor(2, sizes=(11, 3, 1))))
    out2 = tmp_path / "soup2.json"
    assert main([str(out2), str(paths[0]), str(bad)]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "bad.json" in err and "layers" in err
    assert not out2.exists()
