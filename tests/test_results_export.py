"""Results as pandas DataFrames, xarray Datasets and netCDF files (the extra ``netcdf``)."""

import os
import sys

import numpy as np
import pytest
import xarray as xr
from _cli import one_line_error, run_cli

import drillstring as ds
from drillstring.errors import MissingExtraError

ALUMINUM = ds.preset("aluminum")


@pytest.fixture(scope="module")
def modal():
    return ds.simulate(ALUMINUM, modes=3, rigid_mode=True, t_end=0.2, samples=41)


@pytest.fixture(scope="module")
def field():
    return ds.solve_pde(ALUMINUM, nodes=31, t_end=0.05, samples=11)


def test_dataframe_at_the_default_section_is_theta_at_2l_over_3(modal):
    df = modal.to_pandas()
    zk = 2 * ALUMINUM.length / 3
    assert list(df.columns) == ["theta", "theta_dot"] and df.index.name == "t"
    np.testing.assert_array_equal(df.index.to_numpy(), modal.t)
    np.testing.assert_array_equal(df["theta"].to_numpy(), modal.theta(zk))
    np.testing.assert_array_equal(df["theta_dot"].to_numpy(), modal.theta_dot(zk))
    assert df.attrs["units"] == {"t": "s", "z": "m", "theta": "rad", "theta_dot": "rad/s"}
    assert df.attrs["z"] == zk and df.attrs["method"] == "dop853" and df.attrs["status"] == "success"
    assert df.attrs["parameters"]["initial_velocities"] == [0.1, 0.05, 0.02]
    # a real response: the twist at z_k moves by about 5e-4 rad over 0.2 s
    assert 1e-4 < np.abs(df["theta"]).max() < 1e-3


def test_dataframe_at_several_sections_has_two_level_columns(modal, field):
    for res in (modal, field):
        z = [0.0, 25.0, 100.0]
        df = res.to_pandas(z)
        assert df.columns.names == ["quantity", "z"]
        assert df.shape == (res.t.size, 6)
        np.testing.assert_array_equal(df["theta"][25.0].to_numpy(), res.theta(z)[1])
        np.testing.assert_array_equal(df["theta_dot"].to_numpy(), res.theta_dot(z).T)
        assert df.attrs["z"] == z


def test_dataframe_rejects_a_section_outside_the_string(modal):
    with pytest.raises(ds.ValidationError, match="z.*0 <= z <= length = 100"):
        modal.to_pandas(150.0)


def test_modal_dataset_holds_q_of_mode_and_t(modal):
    data = modal.to_xarray()
    assert data["q"].dims == ("mode", "t") and list(data["mode"].values) == [0, 1, 2, 3]
    np.testing.assert_array_equal(data["q"].values, modal.q)
    np.testing.assert_array_equal(data["qdot"].sel(mode=2).values, modal.qdot[2])
    np.testing.assert_array_equal(data["energy"].values, modal.energy)
    assert data["q"].attrs["units"] == "rad" and data["t"].attrs["units"] == "s"
    assert data["energy"].attrs["units"] == "J"
    assert data.attrs["length"] == 100.0 and data.attrs["k5_variant"] == "paper"
    np.testing.assert_array_equal(data.attrs["initial_velocities"], [0.1, 0.05, 0.02])
    assert data.attrs["nfev"] == modal.stats.nfev and data.attrs["status"] == "success"
    # theta(z, t) from the dataset's modes equals the result's
    zk = 2 * ALUMINUM.length / 3
    basis = np.cos(data["mode"].values * np.pi * zk / ALUMINUM.length)
    np.testing.assert_allclose(basis @ data["q"].values, modal.theta(zk), rtol=0, atol=1e-15)


def test_pde_dataset_holds_theta_of_z_and_t(field):
    data = field.to_xarray()
    assert data["theta"].dims == ("z", "t") and data["z"].attrs["units"] == "m"
    np.testing.assert_array_equal(data["z"].values, field.z)
    np.testing.assert_array_equal(data["theta"].sel(z=field.z[10]).values, field.q[10])
    np.testing.assert_array_equal(data["theta_dot"].values, field.qdot)
    # the end node is the section z = l
    np.testing.assert_array_equal(data["theta"].isel(z=-1).values, field.theta(ALUMINUM.length))


@pytest.mark.parametrize("which", ["modal", "field"])
def test_netcdf_round_trip_is_exact(which, request, tmp_path):
    res = request.getfixturevalue(which)
    path = tmp_path / "run.nc"
    assert res.save(path) == path
    with xr.open_dataset(path, engine="h5netcdf") as back:
        xr.testing.assert_identical(back.load(), res.to_xarray())
        assert back.attrs["method"] == "dop853"


def test_save_replaces_a_file_atomically_and_refuses_a_directory(modal, tmp_path):
    path = tmp_path / "run.nc"
    path.write_bytes(b"old")
    os.chmod(path, 0o640)
    modal.save(path)
    assert path.read_bytes()[:8] == b"\x89HDF\r\n\x1a\n" and (path.stat().st_mode & 0o777) == 0o640
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc"]  # no temporary file left
    with pytest.raises(ds.ValidationError, match="path"):
        modal.save(tmp_path)



# --------------------------------------------------------------------------- the extra `netcdf`


@pytest.mark.parametrize("module", ["xarray", "h5netcdf", "h5py"])
def test_netcdf_without_its_extra_names_the_extra_and_writes_nothing(modal, tmp_path, monkeypatch, module):
    monkeypatch.setitem(sys.modules, module, None)  # `import module` raises ImportError
    path = tmp_path / "run.nc"
    message = r"extra 'netcdf' \(" + module + r" not installed\).*'\.\[netcdf\]'"
    with pytest.raises(MissingExtraError, match=message) as e:
        modal.save(path)
    assert isinstance(e.value, ImportError) and e.value.extra == "netcdf" and e.value.missing == (module,)
    assert list(tmp_path.iterdir()) == []


def test_xarray_dataset_without_xarray_names_the_extra(modal, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(MissingExtraError, match=r"\.\[netcdf\]"):
        modal.to_xarray()


def test_cli_writes_the_run_as_netcdf_for_a_name_ending_in_nc(capsys, tmp_path):
    path = tmp_path / "run.nc"
    code, out, _ = run_cli(capsys, "simulate", "--modes", "2", "--t-end", "0.05", "--samples", "11", "--out",
                           str(path), "--no-progress")
    assert code == 0 and f"wrote {path}" in out
    expected = ds.simulate(ALUMINUM, modes=2, t_end=0.05, samples=11)
    with xr.open_dataset(path, engine="h5netcdf") as back:
        np.testing.assert_array_equal(back["q"].values, expected.q)
        np.testing.assert_array_equal(back["energy"].values, expected.energy)


@pytest.mark.parametrize("verb", ["simulate", "pde"])
def test_cli_netcdf_without_its_extra_is_one_line_and_exit_2_before_any_work(capsys, tmp_path, monkeypatch, verb):
    monkeypatch.setitem(sys.modules, "h5netcdf", None)
    code, out, err = run_cli(capsys, verb, "--t-end", "0.05", "--out", str(tmp_path / "run.nc"))
    assert code == 2 and out == ""  # refused before the solve: no summary line
    one_line_error(err, "--out as netCDF", "h5netcdf not installed", "pip install '.[netcdf]'")
    assert list(tmp_path.iterdir()) == []
