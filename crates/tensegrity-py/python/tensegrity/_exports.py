"""The exports of the command line (``tensegrity export mjcf|json|schema``) and the
project's figures (``tensegrity figures --only N``) from Python: each through the same Rust
code the command line runs, in-process (values cross as Python objects, ``src/convert.rs``;
the files are written by the engine's sinks, renamed into place when complete)."""

import json as _json
import os
import shutil
import tempfile

from . import _native
from ._commands import _input, _real

__all__ = ["export_mjcf", "export_json", "export_schema", "figure", "figures"]


def _scene(scene):
    """``scene`` as the engine takes it, and the name the command line would give it."""
    if isinstance(scene, os.PathLike):
        scene = os.fspath(scene)
    if isinstance(scene, str):
        return scene, scene
    if hasattr(scene, "_arrays"):
        return scene, "structure data"
    raise _input("scene", f"scene = {type(scene).__name__}: expected a path, TOML or JSON "
                          "text, or a Structure")


def _write(text, path):
    """Writes ``text`` to ``path`` (through a temporary file renamed into place)."""
    path = os.fspath(path)
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8", newline="") as f:
        f.write(text)
    os.replace(tmp, path)


def export_mjcf(scene, path=None, *, timestep=None, ground_height=None, source=None):
    """MuJoCo's MJCF (XML) of a scene, as ``tensegrity export mjcf SCENE [--out PATH]``
    writes it: every bar a body with a free joint (its mass, the rod inertia m l²/12, a
    capsule, a site at each end), shared and pinned nodes tied by ``<connect>``, every string
    and cluster a spatial tendon (stiffness, damping, no force below its rest length), the
    scene's gravity. Loads, partial or elastic supports, free nodes on no bar, pulley friction
    and actuation tables are refused (:class:`~tensegrity.errors.InputError`, naming the item).

    Parameters
    ----------
    scene : str, os.PathLike or Structure
        A scene file's path, the TOML (or JSON) text of a scene, or a :class:`Structure`.
    path : str or os.PathLike, optional
        Also write the model here (the command line's ``--out``).
    timestep : float, optional
        MuJoCo's time step (s), positive. Default: 0.001.
    ground_height : float, optional
        A ground plane z = ground_height (m) that the bars' capsules touch (default: the
        scene's ``[ground]`` plane, if any).
    source : str, optional
        The name of the model's source in its header (default: the path as given, or
        ``structure data``; the command line writes the path it was given).

    Returns
    -------
    str
        The MJCF text (byte for byte the command line's).
    """
    value, name = _scene(scene)
    step = _real(_native.MJCF_TIMESTEP if timestep is None else timestep, "timestep")
    if step <= 0:
        raise _input("timestep", f"timestep = {step}: must be positive")
    ground = None if ground_height is None else _real(ground_height, "ground_height")
    text = _native.export_mjcf({"scene": value}, name if source is None else str(source),
                               step, ground)
    if path is not None:
        _write(text, path)
    return text


def export_json(scene, path=None):
    """The scene as JSON of the same shape as its TOML (``tensegrity export json SCENE
    [--out PATH]``; every command reads it back: a scene file whose name ends in ``.json``).

    ``scene`` is a path, TOML text or a :class:`Structure`; ``path``: also write it there.
    Returns the JSON text (byte for byte the command line's)."""
    value, _ = _scene(scene)
    text = _native.export_json({"scene": value})
    if path is not None:
        _write(text, path)
    return text


def export_schema(path=None):
    """The JSON Schema of scene files, TOML or JSON (``tensegrity export schema [--out
    PATH]``), generated from the scene description. ``path``: also write the text there.
    Returns the schema as a dict."""
    text = _native.export_schema()
    if path is not None:
        _write(text, path)
    return _json.loads(text)


def figures():
    """The project's figures: ``{number: description}`` (``"3.10"``, …), the names
    :func:`figure` takes."""
    return {number: description for number, description, _ in _native.figures()}


def figure(name, path, size=None, dpi=None, *, quick=False, data=True, max_memory=None,
           max_work=None, max_output=None):
    """Writes one of the project's figures, as ``tensegrity figures --only NAME`` draws it,
    built and rendered in-process by the same Rust code.

    Parameters
    ----------
    name : str
        The figure's number (``"3.10"``, ``"5.2"``) or file stem (``"fig_3_10"``); the
        known ones: :func:`figures`.
    path : str or os.PathLike
        The file to write; its extension picks the format: ``.svg``, ``.png`` (embedded font,
        ``dpi`` pixels per inch) or ``.pdf`` (one page). Renamed into place once complete.
    size : str, optional
        Figure size ``WIDTHxHEIGHT`` with a unit px (default), in, cm, mm or pt, e.g.
        ``"6x4in"`` or ``"16x10cm"`` (the command line's ``--size``; default: the figure's own
        size in px). A PDF's page is this size.
    dpi : float, optional
        Resolution of a PNG in pixels per inch, 10 to 2400 (``--dpi``; default 96, one pixel
        per px).
    quick : bool, optional
        Coarser grids and shorter runs (``--quick``).
    data : bool or str or os.PathLike, optional
        Write the figure's data table as CSV (``True``: beside the figure, its name with
        ``.csv``, as the command line does; a path: there; ``False``: not).
    max_memory, max_work, max_output : float or str, optional
        Refuse the figure when its estimate is above these limits (as every function).

    Returns
    -------
    str
        The path written.
    """
    if not isinstance(name, str):
        raise _input("name", f"name = {name!r}: expected a figure number such as '3.10'")
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".svg", ".png", ".pdf"):
        raise _input("path", f"path = {path!r}: the extension must be .svg, .png or .pdf")
    if data is True:
        data_path = os.path.splitext(path)[0] + ".csv"
    elif data is False or data is None:
        data_path = None
    else:
        data_path = os.fspath(data)
    if size is not None and not isinstance(size, str):
        raise _input("size", f"size = {size!r}: expected text such as '6x4in'")
    dpi = None if dpi is None else _real(dpi, "dpi")
    limits = {"max_memory": max_memory, "max_work": max_work, "max_output": max_output}
    sweeps = tempfile.mkdtemp(prefix="tensegrity-figure-")
    try:
        _native.figure(name, path, data_path, sweeps, bool(quick), limits, size, dpi)
    finally:
        shutil.rmtree(sweeps, ignore_errors=True)
    return path
