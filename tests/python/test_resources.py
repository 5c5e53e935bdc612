"""Threads, memory and Ctrl-C of `trichart build`: the same atlas for every thread count, a
request too large for memory refused before the work starts, SIGINT stopping a build cleanly."""
import hashlib
import os
import re
import signal
import subprocess
import sys
import time

import pytest


def run(*args, **kwargs):
    return subprocess.run([sys.executable, "-m", "trichart", *map(str, args)],
                          capture_output=True, text=True, timeout=300, **kwargs)


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def leftovers(folder):
    """Every file in `folder`: after a refused or interrupted build, none (no atlas, no
    temporary file)."""
    return sorted(os.listdir(folder))


def test_the_atlas_is_the_same_bytes_with_1_and_2_threads_and_twice(testing_data, tmp_path):
    mesh = testing_data / "meshes" / "bunny_npm.off"
    digests = []
    for name, threads in (("a", 1), ("b", 2), ("c", 2), ("d", 1)):
        r = run("build", mesh, "-o", tmp_path / f"{name}.exr", "-q", "--threads", threads)
        assert r.returncode == 0, r.stderr
        digests.append(digest(tmp_path / f"{name}.exr"))
    assert len(set(digests)) == 1, digests


def test_the_nystrom_clustering_and_a_large_budget_are_deterministic_too(testing_data,
                                                                         tmp_path):
    """In process, through pipeline.build: the Nystrom path of the clustering (its threshold
    lowered below the fandisk's 12946 faces) and the error rule on a budget 30 times the
    points."""
    import trichart
    from trichart import tcResources

    mesh = testing_data / "meshes" / "fandisk.off"
    digests = []
    try:
        for name, threads in (("a", 1), ("b", 2), ("c", 2)):
            trichart.set_max_threads(threads)
            assert tcResources.GetMaxThreads() == threads
            result = trichart.build(mesh, tmp_path / f"{name}.exr", retry_slivers=False,
                                    cluster_options={"nystrom_threshold": 1000},
                                    geometry_options={"sample_budget": 200000})
            digests.append(digest(result["files"]["atlas"]))
    finally:
        trichart.set_max_threads(0)
    assert len(set(digests)) == 1, digests


def test_threads_outside_the_range_are_refused(testing_data, tmp_path):
    r = run("build", testing_data / "meshes" / "cube.off", "-o", tmp_path / "a.exr",
            "--threads", "-2")
    assert r.returncode == 2 and "--threads must be 1 .. 4096" in r.stderr, r.stderr


def test_a_request_that_cannot_be_estimated_is_refused(testing_data, tmp_path):
    for option in (["--budget", "-5"], ["--max-level", "13"]):
        r = run("build", testing_data / "meshes" / "cube.off", "-o", tmp_path / "a.exr", "-q",
                *option)
        assert r.returncode == 2, r.stderr
        assert "the budget must not be negative and the largest level must be 0 .. 12" in \
            r.stderr, r.stderr
        assert not (tmp_path / "a.exr").exists()


def test_memory_sizes_take_units():
    from trichart.cli import memory_size

    assert memory_size("8G") == 8 * 2 ** 30
    assert memory_size("512M") == 512 * 2 ** 20
    assert memory_size("1.5g") == 3 * 2 ** 29
    assert memory_size("64MiB") == 64 * 2 ** 20
    assert memory_size("2T") == 2 * 2 ** 40
    assert memory_size("1000") == 1000
    for bad in ("", "8X", "-1G", "G", "1.2.3M"):
        with pytest.raises(Exception, match="no memory size"):
            memory_size(bad)


PLY_100M = (b"ply\nformat binary_little_endian 1.0\nelement vertex 50000000\n"
            b"property float x\nproperty float y\nproperty float z\nelement face 100000000\n"
            b"property list uchar int vertex_indices\nend_header\n" + bytes(1000))


def test_a_100m_triangle_file_is_refused_before_the_work_with_the_estimate(tmp_path):
    """The header declares 100M faces (the body is missing: the refusal never reads it). At the
    default limit, the machine's available memory, when that is below the estimate; with
    --max-memory in every case."""
    import trichart
    from trichart import tcResources

    mesh = tmp_path / "huge.ply"
    mesh.write_bytes(PLY_100M)
    out = tmp_path / "out"
    out.mkdir()
    estimate = trichart.estimate_memory(50000000, 100000000)
    assert estimate > 60 * 2 ** 30
    limits = [["--max-memory", "16G"]]
    if tcResources.GetAvailableMemory() < estimate:
        limits.append([])
    for limit in limits:
        start = time.perf_counter()
        r = run("build", mesh, "-o", out / "huge.exr", "-q", *limit)
        seconds = time.perf_counter() - start
        assert r.returncode == 2, r.stderr
        assert "100000000 triangles" in r.stderr and "needs about" in r.stderr, r.stderr
        assert f"{estimate / 2 ** 30:.1f} GB" in r.stderr, r.stderr
        assert ("16.0 GB" if limit else "the available memory") in r.stderr, r.stderr
        assert seconds < 30, seconds  # a sanity bound, not a benchmark: it reads 64 KiB
        assert leftovers(out) == []


def test_a_budget_beyond_the_limit_is_refused_and_one_within_it_builds(testing_data,
                                                                      tmp_path):
    mesh = testing_data / "meshes" / "bunny_npm.off"
    r = run("build", mesh, "-o", tmp_path / "a.exr", "-q", "--budget", "2000000000",
            "--max-level", "12", "--max-memory", "8G")
    assert r.returncode == 2, r.stderr
    assert "a budget of 2000000000 samples up to level 12" in r.stderr, r.stderr
    assert "limit of 8.0 GB (--max-memory" in r.stderr, r.stderr
    assert not (tmp_path / "a.exr").exists()
    # The same budget capped at level 8 is 100 charts x 33153 samples: it fits and builds.
    r = run("build", mesh, "-o", tmp_path / "b.exr", "-q", "--budget", "2000000000",
            "--max-memory", "8G")
    assert r.returncode == 0, r.stderr
    assert "memory: peak" in r.stdout and "estimated" in r.stdout


def test_the_estimate_covers_the_peak_of_a_build(testing_data, tmp_path):
    """The summary's line: the peak resident memory lies below the memory held at the start
    plus the estimate."""
    r = run("build", testing_data / "meshes" / "fandisk.off", "-o", tmp_path / "a.exr", "-q")
    assert r.returncode == 0, r.stderr
    figures = re.search(r"memory: peak (\d+) MB resident, estimated (\d+) MB above the (\d+) MB",
                        r.stdout)
    assert figures, r.stdout
    peak, estimate, start = (int(v) for v in figures.groups())
    assert estimate > 0 and peak <= start + estimate, figures.group(0)


def _interrupt_during(mesh, stage, folder, *options):
    """Starts `trichart build` on `mesh`, sends SIGINT once its progress reaches `stage`;
    returns (exit code, stderr)."""
    p = subprocess.Popen([sys.executable, "-m", "trichart", "build", str(mesh), "-o",
                          str(folder / "atlas.exr"), *options], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    lines = []
    for line in p.stderr:  # "stage: N%" lines: stderr is no terminal
        lines.append(line)
        if line.startswith(f"{stage}:"):
            p.send_signal(signal.SIGINT)
            break
    else:
        p.wait(timeout=300)
        pytest.fail(f"the build ended before {stage}: {''.join(lines)}")
    _, rest = p.communicate(timeout=300)
    return p.returncode, "".join(lines) + rest


@pytest.mark.parametrize("stage", ["clusters", "images"])
def test_sigint_stops_the_build_and_leaves_no_file(shared_data, tmp_path, stage):
    mesh = shared_data / "static_medium" / "bunny00.off"
    if not mesh.exists():
        pytest.skip(f"{mesh} is absent")
    # A budget 40 times the points keeps the geometry images running for seconds.
    code, err = _interrupt_during(mesh, stage, tmp_path, "--budget", "1600000",
                                  "--max-level", "10")
    assert code == 130, err
    assert "trichart: interrupted" in err and "Traceback" not in err, err
    assert leftovers(tmp_path) == []
