"""Fault corpus, part 2 (issue 24): outputs own only what they wrote; only regular files are written over.

Each case failed on the code before the manifest (``microimpact.io.owned_directory``): the output
folders of ``export`` and ``paper`` were claimed by file-name patterns and swapped whole, and a
device, FIFO or socket at an output path was written to or renamed over.
"""

from __future__ import annotations

import json
import os
import socket
import stat
import subprocess
import sys

import pytest

from microimpact import io as mio

from .test_faults import ROOT, _env, assert_one_line, no_temp_files, run

DATA = "velocity,restitution\n5,1.0\n20,0.86\n50,0.72\n80,0.64\n"


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def listing(folder):
    return sorted(p.name for p in folder.iterdir())


# ----------------------------------------------------------------------------- 1. a folder is owned by its manifest
def test_export_never_touches_its_input_inside_the_output_folder(work, capsys):
    (work / "cfd").mkdir()
    (work / "cfd" / "restitution_measured.csv").write_text(DATA)
    rc, out, err = run(["export", "--out", "cfd", "--fit", "cfd/restitution_measured.csv"], capsys)
    assert_one_line(rc, err, "restitution_measured.csv", "input")
    assert listing(work / "cfd") == ["restitution_measured.csv"]
    assert (work / "cfd" / "restitution_measured.csv").read_text() == DATA


def test_export_keeps_a_users_files_of_its_own_names(work, capsys):
    d = work / "d"
    d.mkdir()
    (d / "README.txt").write_text("my notes\n")
    (d / "restitution_wall_si_2025.csv").write_text(DATA)
    rc, out, err = run(["export", "--out", "d"], capsys)
    assert_one_line(rc, err, "README.txt")  # the first foreign file, by name
    assert (d / "README.txt").read_text() == "my notes\n"
    assert (d / "restitution_wall_si_2025.csv").read_text() == DATA
    assert listing(d) == ["README.txt", "restitution_wall_si_2025.csv"]


def test_paper_in_the_working_directory_keeps_a_users_files(work, capsys):
    for name in ("report.md", "fig01.png", "comparison.csv"):
        (work / name).write_text(f"the user's {name}\n")
    inode = os.stat(work).st_ino
    rc, out, err = run(["paper", "--out", ".", "--quiet"], capsys)
    assert_one_line(rc, err, "comparison.csv")
    for name in ("report.md", "fig01.png", "comparison.csv"):
        assert (work / name).read_text() == f"the user's {name}\n"
    assert listing(work) == ["comparison.csv", "fig01.png", "report.md"]
    assert os.stat(work).st_ino == inode


def test_a_later_run_replaces_and_deletes_only_what_the_manifest_lists(work, capsys):
    rc, out, err = run(["export", "--out", "d", "--diameters", "1e-6,2e-6", "--no-c"], capsys)
    assert rc == 0, err
    first = listing(work / "d")
    assert first == [mio.MANIFEST, "restitution_d1um.csv", "restitution_d2um.csv", "restitution_vs_v_over_vy.csv"]
    doc = json.loads((work / "d" / mio.MANIFEST).read_text())
    assert doc["command"] == "export" and sorted(doc["files"]) == first[1:]
    rc, out, err = run(["export", "--out", "d", "--diameters", "3e-6"], capsys)
    assert rc == 0, err  # the earlier run's files: proven by the manifest, replaced or deleted
    assert listing(work / "d") == [
        mio.MANIFEST,
        "microimpact_wall.c",
        "restitution_d3um.csv",
        "restitution_vs_v_over_vy.csv",
    ]
    assert sorted(json.loads((work / "d" / mio.MANIFEST).read_text())["files"]) == listing(work / "d")[1:]


def test_a_file_edited_since_it_was_written_is_the_users(work, capsys):
    assert run(["export", "--out", "d", "--no-c"], capsys)[0] == 0
    table = work / "d" / "restitution_vs_v_over_vy.csv"
    table.write_text(table.read_text() + "# my annotation\n")
    edited = table.read_text()
    rc, out, err = run(["export", "--out", "d", "--no-c"], capsys)
    assert_one_line(rc, err, "restitution_vs_v_over_vy.csv", "changed")
    assert table.read_text() == edited


def test_a_forged_or_foreign_manifest_proves_nothing(work, capsys):
    d = work / "d"
    d.mkdir()
    (d / "notes.txt").write_text("precious\n")
    (d / mio.MANIFEST).write_text(json.dumps({"format": "microimpact-manifest", "command": "export", "files": {}}))
    rc, out, err = run(["export", "--out", "d"], capsys)
    assert_one_line(rc, err, "notes.txt")
    assert (d / "notes.txt").read_text() == "precious\n"
    # another command's output folder is not this command's
    assert run(["export", "--out", "e", "--no-c"], capsys)[0] == 0
    rc, out, err = run(["paper", "--out", "e", "--quiet"], capsys)
    assert_one_line(rc, err, "export")


def test_out_dot_writes_into_the_working_directory_in_place(work, capsys):
    inode = os.stat(work).st_ino
    for diameters in ("1e-6", "2e-6"):
        rc, out, err = run(["export", "--out", ".", "--diameters", diameters, "--no-c"], capsys)
        assert rc == 0, err
        assert os.stat(".").st_ino == inode and os.getcwd() == str(work)  # the shell's folder is not swapped
    assert listing(work) == [mio.MANIFEST, "restitution_d2um.csv", "restitution_vs_v_over_vy.csv"]
    sub = work / "sub"
    sub.mkdir()
    os.chdir(sub)
    (work / "sub" / "mine.txt").write_text("x")
    rc, out, err = run(["export", "--out", "..", "--no-c"], capsys)  # an ancestor of the cwd
    assert_one_line(rc, err, "sub")
    assert (sub / "mine.txt").read_text() == "x" and os.stat(work).st_ino == inode


def test_paper_data_file_inside_the_output_folder_is_refused(work, capsys):
    (work / "p").mkdir()
    (work / "p" / "wall.csv").write_text(DATA)
    rc, out, err = run(["paper", "--out", "p", "--quiet", "--data", "silicon=p/wall.csv"], capsys)
    assert_one_line(rc, err, "wall.csv")
    assert listing(work / "p") == ["wall.csv"]


def test_owned_directory_refuses_subfolders_and_symlinks(tmp_path):
    out = tmp_path / "out"
    with mio.owned_directory(out, "test") as tmp:
        (tmp / "a.txt").write_text("1")
    (out / "link").symlink_to(out / "a.txt")  # a link to an owned file is not an owned file
    with pytest.raises(FileExistsError, match="link"):
        with mio.owned_directory(out, "test"):
            pass
    (out / "link").unlink()
    (out / "sub").mkdir()
    with pytest.raises(FileExistsError, match="sub"):
        with mio.owned_directory(out, "test"):
            pass
    assert (out / "a.txt").read_text() == "1" and no_temp_files(tmp_path) == []


# ----------------------------------------------------------------------------- 2. only regular files are written over
def _fifo(work, sfx):
    path = work / f"fifo{sfx}"
    os.mkfifo(path)
    return path


def _socket(work, sfx):
    path = work / f"sock{sfx}"
    s = socket.socket(socket.AF_UNIX)
    s.bind(str(path))
    return path, s


@pytest.mark.parametrize("kind", ["fifo", "socket", "/dev/null"])
@pytest.mark.parametrize(
    "argv",
    [
        ["history", "50", "--n", "5", "--out", "{}"],
        ["sweep", "--velocity", "1,2", "--out", "{}"],
        ["fit", "data.csv", "--plot", "{}"],
        ["history", "50", "--n", "5", "--out", "h.csv", "--plot", "{}"],
    ],
    ids=["history", "sweep", "fit", "history-plot"],
)
def test_special_files_are_refused_before_any_work(work, capsys, kind, argv):
    (work / "data.csv").write_text(DATA)
    keep = None
    sfx = ".png" if "--plot" in argv else ".csv"
    if kind == "fifo":
        path = _fifo(work, sfx)
    elif kind == "socket":
        path, keep = _socket(work, sfx)
    elif argv[0] == "history" and sfx == ".csv":
        path = "/dev/null"
    else:
        pytest.skip("the command needs a suffix /dev/null has not")
    try:
        argv = [a.replace("{}", str(path)) for a in argv]
        rc, out, err = run(argv, capsys)
        assert_one_line(rc, err, os.path.basename(str(path)), "regular file")
        assert not (work / "h.csv").exists()
        if kind == "fifo":
            assert stat.S_ISFIFO(os.lstat(path).st_mode)
        elif kind == "socket":
            assert stat.S_ISSOCK(os.lstat(path).st_mode)
        else:
            assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
        assert no_temp_files(work) == []
    finally:
        if keep is not None:
            keep.close()


def test_a_symlink_is_followed_and_its_target_replaced(work, capsys):
    (work / "real.csv").write_text("old\n")
    (work / "link.csv").symlink_to("real.csv")
    rc, out, err = run(["history", "50", "--n", "5", "--out", "link.csv"], capsys)
    assert rc == 0, err
    assert (work / "link.csv").is_symlink() and os.readlink(work / "link.csv") == "real.csv"
    assert (work / "real.csv").read_text().startswith("time [s]")
    (work / "dangling.csv").symlink_to("nowhere/x.csv")  # its target's folder is missing: refused, naming it
    rc, out, err = run(["history", "50", "--n", "5", "--out", "dangling.csv"], capsys)
    assert_one_line(rc, err, "nowhere")


def test_standard_output_dash_still_works(work, capsys):
    rc, out, err = run(["history", "50", "--n", "5", "--out", "-"], capsys)
    assert rc == 0 and out.startswith("time [s]"), err


@pytest.mark.parametrize("target", ["/dev/full", "/dev/null", "adir"])
def test_bench_json_is_checked_before_the_suite_runs(work, capsys, target):
    (work / "adir").mkdir()
    rc, out, err = run(["bench", "--tiny", "--suite", str(ROOT / "benchmarks"), "--json", target], capsys)
    assert_one_line(rc, err, target)
    assert "running the benchmark suite" not in err
    assert listing(work) == ["adir"] and listing(work / "adir") == []  # no adir.tmpPID, nothing in it
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode) and stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_export_to_a_device_is_refused(work):
    proc = subprocess.run(
        [sys.executable, "-m", "microimpact", "export", "--out", "/dev/null"],
        capture_output=True,
        text=True,
        env=_env(),
    )
    assert_one_line(proc.returncode, proc.stderr, "/dev/null")


# ----------------------------------------------------------------------------- 3. a folder is committed all or nothing
def _contents(folder):
    return {p.name: (p.read_bytes() if p.is_file() else "dir") for p in folder.iterdir()}


def test_a_rename_that_fails_leaves_the_earlier_output_and_its_manifest(tmp_path):
    out = tmp_path / "out"
    with mio.owned_directory(out, "test") as stage:
        (stage / "a.txt").write_text("old a")
        (stage / "b.txt").write_text("old b")
    before = _contents(out)
    with pytest.raises(IsADirectoryError) as exc:
        with mio.owned_directory(out, "test") as stage:
            for name in ("a.txt", "b.txt", "c.txt"):
                (stage / name).write_text("new " + name)
            (out / "c.txt").mkdir()  # a directory in the way of the last file, made while the run wrote
    # the error names the user's file, not a staging path; the earlier files and manifest are back
    assert exc.value.filename == os.path.join(str(out), "c.txt") and exc.value.filename2 is None
    assert ".microimpact-" not in str(exc.value)
    assert _contents(out) == {**before, "c.txt": "dir"} and no_temp_files(out) == []
    (out / "c.txt").rmdir()
    with mio.owned_directory(out, "test") as stage:  # the folder is still this command's: a later run replaces it
        (stage / "c.txt").write_text("new c")
    assert listing(out) == [mio.MANIFEST, "c.txt"] and no_temp_files(out) == []


def test_an_export_whose_commit_fails_can_run_again(work, capsys, monkeypatch):
    import errno

    assert run(["export", "--out", "d", "--no-c"], capsys)[0] == 0
    before = _contents(work / "d")
    rename = os.rename

    def failing(src, dst, *args, **kw):  # the disk fails on the second file put in place
        if ".microimpact-staging." in os.fspath(src) and os.fspath(dst).endswith("restitution_vs_v_over_vy.csv"):
            raise OSError(errno.EIO, "Input/output error", os.fspath(src), None, os.fspath(dst))
        return rename(src, dst, *args, **kw)

    monkeypatch.setattr(os, "rename", failing)
    rc, out, err = run(["export", "--out", "d", "--no-c", "--diameters", "3e-6"], capsys)
    assert_one_line(rc, err, os.path.join("d", "restitution_vs_v_over_vy.csv"), "input/output error")
    assert "staging" not in err and ".tmp" not in err
    assert _contents(work / "d") == before and no_temp_files(work / "d") == []
    monkeypatch.setattr(os, "rename", rename)
    rc, out, err = run(["export", "--out", "d", "--no-c", "--diameters", "3e-6"], capsys)
    assert rc == 0, err
    assert listing(work / "d") == [mio.MANIFEST, "restitution_d3um.csv", "restitution_vs_v_over_vy.csv"]


def test_an_interrupt_during_the_commit_undoes_it(tmp_path, monkeypatch):
    out = tmp_path / "out"
    with mio.owned_directory(out, "test") as stage:
        (stage / "a.txt").write_text("old a")
    before = _contents(out)
    rename = os.rename
    calls = []

    def interrupted(src, dst, *args, **kw):  # Ctrl-C after the first new file is in place
        rename(src, dst, *args, **kw)
        calls.append(dst)
        if ".microimpact-staging." in os.fspath(src):
            raise KeyboardInterrupt

    monkeypatch.setattr(os, "rename", interrupted)
    with pytest.raises(KeyboardInterrupt):
        with mio.owned_directory(out, "test") as stage:
            (stage / "a.txt").write_text("new a")
            (stage / "b.txt").write_text("new b")
    monkeypatch.setattr(os, "rename", rename)
    assert calls and _contents(out) == before and no_temp_files(out) == []


# ----------------------------------------------------------------------------- 4. the manifest read back
def test_a_manifest_that_is_a_link_is_not_followed(work, capsys):
    assert run(["export", "--out", "d", "--no-c"], capsys)[0] == 0
    elsewhere = work / "elsewhere.json"
    os.replace(work / "d" / mio.MANIFEST, elsewhere)
    (work / "d" / mio.MANIFEST).symlink_to(elsewhere)
    kept = elsewhere.read_bytes()
    with pytest.raises(ValueError, match="symbolic link"):
        with mio.owned_directory(work / "d", "export"):
            pass
    rc, out, err = run(["export", "--out", "d", "--no-c"], capsys)
    assert_one_line(rc, err, mio.MANIFEST, "symbolic link")
    assert elsewhere.read_bytes() == kept and (work / "d" / mio.MANIFEST).is_symlink()


@pytest.mark.parametrize("kind", ["fifo", "too large"])
def test_a_manifest_that_is_no_small_regular_file_is_refused(tmp_path, kind):
    out = tmp_path / "out"
    with mio.owned_directory(out, "test") as stage:
        (stage / "a.txt").write_text("a")
    (out / mio.MANIFEST).unlink()
    if kind == "fifo":
        os.mkfifo(out / mio.MANIFEST)  # reading it would block for ever
        match = "not a regular file"
    else:
        with open(out / mio.MANIFEST, "wb") as fh:
            fh.truncate(mio.MANIFEST_MAX_BYTES + 1)
        match = "larger than"
    with pytest.raises(ValueError, match=match) as exc:
        with mio.owned_directory(out, "test"):
            pass
    assert len(str(exc.value).splitlines()) == 1 and str(out) in str(exc.value)
    assert listing(out) == [mio.MANIFEST, "a.txt"]
