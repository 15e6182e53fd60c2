"""python/examples/fleet.py on a dask.distributed LocalCluster (Debian's python3-distributed):
a directory of three bundled captures, one task per capture, on two in-process workers (threads:
no processes to start on a busy machine; the whole run bounded by a timeout). Each capture's stats
equal `hesai stats --json` of it (the program, run here), and the merged counts equal the sum of
those JSON objects, summed by this test.
"""

import importlib.util
import json
import subprocess

import pytest

from test_package import CLI, DATA, ROOT

from dask.distributed import Client, LocalCluster  # python3-distributed (.ci/install-deps): a failure, not a skip

CAPTURES = ["pandar_xt16", "pandar_xt32m2x", "pandar_qt64"]
# `stats --json` values that are no counts: not summed by a merge (first/last: min and max).
NOT_COUNTS = {"first_time_ns", "last_time_ns", "fs_last_fault_code", "fs_last_fault_id", "fs_last_fault_total"}


def load_example():
    spec = importlib.util.spec_from_file_location("fleet", ROOT / "python" / "examples" / "fleet.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def fleet_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("fleet")
    for name in CAPTURES:
        (d / f"{name}.pcap").symlink_to(DATA / f"{name}.pcap")
    (d / "notes.txt").write_text("not a capture")
    return d


def test_fleet_on_a_local_cluster(fleet_dir):
    fleet = load_example()
    captures = sorted(str(p) for p in fleet_dir.glob("*.pcap"))
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        workers = set(client.scheduler_info()["workers"])
        result = fleet.run(client, captures, timeout=300)
    assert len(workers) == 2
    assert [r["path"] for r in result["captures"]] == captures  # one task per capture
    assert all(r["worker"] in workers for r in result["captures"])
    want = {}
    for r in result["captures"]:
        run = subprocess.run([CLI, "stats", r["path"], "--json"], check=True, capture_output=True)
        want[r["path"]] = json.loads(run.stdout)
        assert r["stats"] == want[r["path"]]
        assert r["points"] == want[r["path"]]["points"]  # decode_columns: every point decoded
    # The sum of the program's objects, key by key.
    objs = list(want.values())
    merged = result["stats"]
    checked = 0
    for key in objs[0]:
        values = [o[key] for o in objs]
        if key in NOT_COUNTS:
            continue
        if all(isinstance(v, int) for v in values):
            assert merged[key] == sum(values), key
        elif all(isinstance(v, dict) for v in values):  # models, fs_states
            assert merged[key] == {k: sum(o[key].get(k, 0) for o in objs) for o in objs for k in o[key]}, key
        elif all(isinstance(v, list) for v in values) and key == "blockage_by_channel":
            width = max(len(v) for v in values)
            assert merged[key] == [sum(v[i] for v in values if i < len(v)) for i in range(width)], key
        else:
            continue
        checked += 1
    assert checked >= 35
    assert merged["first_time_ns"] == min(o["first_time_ns"] for o in objs)
    assert merged["last_time_ns"] == max(o["last_time_ns"] for o in objs)
    assert merged["packets"] == 1626 + 1815 + 1200  # the captures' packets (docs/TESTING.md)
    assert merged["models"] == {"PandarXT16": 1626, "PandarXT32M2X": 1815, "PandarQT64": 1200}
    assert merged["lost"] == 852  # the XT32M2X capture's three sequence gaps


def test_fleet_reports_a_damaged_capture(fleet_dir, tmp_path):
    """A task's failure reaches the client as the package's exception, naming the capture."""
    fleet = load_example()
    bad = tmp_path / "bad.pcap"
    bad.write_bytes(b"\0" * 64)
    import hesai
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        with pytest.raises(hesai.HesaiError) as e:
            fleet.run(client, [str(bad)], timeout=120)
    assert e.value.status == 2
