"""Loading a mechanism: a registered name or a description file, resolved and built into a `Mechanism`."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from mechkit import actuator_names, core, sources
from mechkit.base import arguments, joint_arguments
from mechkit.base.exceptions import IgnoredClosure, InvalidArgument, InvalidParameters, MalformedDescription
from mechkit.bases.carrier import with_base
from mechkit.catalog.contract import MechanismSpec
from mechkit.catalog.params import MechanismParams
from mechkit.catalog.registry import get_spec, names
from mechkit.mechanism import Mechanism
from mechkit.reduction import description_of, locked_joints, reduce_description
from mechkit.sources.drake_elements import compliant
from mechkit.sources.physical import check_model
from mechkit.sources.urdf import build_model, parse_loops, parse_springs, parse_xml
from mechkit.sources.xacro_file import render_urdf


def resolve(source: str | Path) -> str | Path:
    """A registered name (returned as `str`) or an existing description file (returned as `Path`).

    A string is a name when it is registered; otherwise, or when it is a `Path` or looks like a path
    (a separator or a known suffix), it must be a readable file.

    Args:
        source: a registered name (`mechkit list`) or a path to a description file.

    Returns:
        The name as `str`, or the file as a `Path` (`~` expanded).

    Raises:
        InvalidParameters: neither a registered name nor a path (the message lists the names).
        MalformedDescription: the path does not exist or is a directory.
    """
    if isinstance(source, str) and source in names():
        return source
    text = str(source)
    looks_like_path = isinstance(source, Path) or "/" in text or "\\" in text or text.endswith(sources.SUFFIXES)
    if not looks_like_path:
        raise InvalidParameters("source", text, f"no such mechanism and not a path; registered: {', '.join(names())}")
    path = Path(text).expanduser()
    if not path.exists():
        raise MalformedDescription(text, "no such file")
    if path.is_dir():
        raise MalformedDescription(text, "is a directory, not a description file")
    return path


def load(
    source: str | Path,
    *,
    actuated: Sequence[str] | None = None,
    home: Mapping[str, float] | None = None,
    guess: Mapping[str, float] | None = None,
    lock: Mapping[str, Any] | None = None,
    keep: Sequence[str] | None = None,
    fix: Sequence[str] | None = None,
    freeflyer: bool = False,
    ignore_unknown_closures: bool = False,
    bushings: str = "rigid",
    base: str = "fixed",
    base_inertia: Any = None,
    gravity: Sequence[float] | None = None,
    **params: Any,
) -> Mechanism:
    """Build a mechanism from a registered name or a description file.

    The file formats (`mechkit.sources`): a `.urdf` with `<mechkit:loop>`s (and `<mimic>` joints,
    read as coupling rows); a `.urdf` with an Extended-URDF `.yaml` sidecar beside it (Gepetto's
    example-parallel-robots); a URDF+ `.urdf` (`<loop>` / `<coupling>` elements); a `.xacro`; an
    MJCF `.xml` (MuJoCo Menagerie: ball and free joints, equalities, tendons, springs, the keyframe
    "home"); an SDFormat `.sdf` (loops of ball, universal and gearbox joints).

    Args:
        source: a registered name (`mechkit list`) or a path to a file of one of those formats.
        actuated: actuated joints, overriding what the file (or the spec) declares.
        home: joint -> value (rad or m) of the default assembly's inputs (default: the file's
            `<mechkit:home>`, MJCF keyframe "home" or qpos0, else none: every loop closed from the guess).
        guess: joint -> value near which the default assembly is sought.
        lock: joint -> value at which it is locked (welded; `mechkit.reduction`).
        keep: bodies whose subsystem alone stays free (every other joint locked at home).
        fix: bodies whose own joint is locked at home (a floating root, for statics).
        freeflyer: put an Extended-URDF file's tree on a free-flyer root joint ("root_joint"), as
            Gepetto's loader does when asked (its legged robots float).
        ignore_unknown_closures: load a file holding another tool's loop closures that mechkit does not
            read (Drake's constraints and bushings, a Gazebo joint: `mechkit.sources.closure_elements`)
            as its tree without them, with one `IgnoredClosure` warning per element naming the mobility
            left (default: refused by name).
        bushings: "rigid" (default): a Drake `drake:linear_bushing_rpy` is the cut its stiff directions make;
            "compliant": a URDF's (or xacro's) are force elements (`mechkit.forces.bushing`, applied by the
            simulator), their loops left open (not with `lock`, `keep` or `fix`).
        base: "fixed" (the ground is the world), "moving" (the ground on six driven root joints that a
            carrier's motion drives) or "floating" (the ground a free body on a free-flyer): `mechkit.bases`.
        base_inertia: the base body's added inertia, (mass kg, (Ixx, Iyy, Izz) kg m^2) or a `pin.Inertia`
            (a floating base needs a mass).
        gravity: (3,) world gravity (m/s^2; (0, 0, 0) in orbit), or None (the model's).
        **params: the mechanism's parameters (a name) or xacro arguments (a xacro file);
            `rows="spatial"`, unless the mechanism has a parameter of that name, closes every cut
            with its full rows.

    Returns:
        The assembled mechanism, at its home assembly (`Mechanism.home_q`).

    Raises:
        InvalidParameters: unknown name or parameter.
        InvalidArgument: `source` neither a name nor a path; `freeflyer` for a source that is not an
            Extended-URDF file; a bad base, base inertia or gravity.
        MalformedDescription: a bad file.
    """
    if not isinstance(source, (str, Path)):
        raise InvalidArgument("source", source, "expected a mechanism name or a path")
    freeflyer = arguments.flag("freeflyer", freeflyer)
    ignore = arguments.flag("ignore_unknown_closures", ignore_unknown_closures)
    if bushings not in ("rigid", "compliant"):
        raise InvalidArgument("bushings", bushings, "expected 'rigid' or 'compliant'")
    if bushings == "compliant" and (lock or keep is not None or fix):  # a reduced tree's URDF drops the marks
        raise InvalidArgument("bushings", bushings, "not with lock, keep or fix: weld or fix joints in the file")
    if bushings == "compliant" and base != "fixed":  # the based tree is built, without the URDF's marks
        raise InvalidArgument("bushings", bushings, f"not on a {base} base: the bushing forces would be lost")
    if base != "fixed" or base_inertia is not None or gravity is not None:
        kwargs = {"lock": lock, "keep": keep, "fix": fix, "freeflyer": freeflyer, "ignore_unknown_closures": ignore}
        kwargs["bushings"] = bushings
        grounded = load(source, actuated=actuated, home=home, guess=guess, **kwargs, **params)
        return with_base(grounded, base, base_inertia=base_inertia, gravity=gravity)
    if lock or keep is not None or fix:
        whole = load(
            source,
            actuated=actuated,
            home=home,
            guess=guess,
            freeflyer=freeflyer,
            ignore_unknown_closures=ignore,
            bushings=bushings,
            **params,
        )
        rows = params.get("rows") if "rows" not in {f.name for f in dataclasses.fields(whole.spec.params)} else None
        reduced = reduce_description(whole, description_of(whole), locked_joints(whole, lock, keep, fix))
        return from_description(reduced, rows=rows)
    where = resolve(source)
    if isinstance(where, Path):
        declared = sources.xacro_args(where) if where.name.endswith(".xacro") else {}
        rows = None if "rows" in declared else params.pop("rows", None)
        description = sources.read(where, params, freeflyer=freeflyer, ignore_unknown_closures=ignore)
        description = compliant(description) if bushings == "compliant" else description
        mechanism = from_description(description, actuated, home, guess, rows)
        for element in description.ignored_closures:
            warnings.warn(
                IgnoredClosure(
                    f"{element}: ignored as asked; the model is left with {mechanism.home_mobility.dof} degree(s) "
                    f"of freedom"
                ),
                stacklevel=2,
            )
        return mechanism
    if freeflyer:
        raise InvalidArgument(
            "freeflyer",
            freeflyer,
            f"{where!r} is a registered mechanism: only an Extended-URDF "
            "file (a .urdf with a .yaml sidecar) takes a free-flyer root",
        )
    spec = get_spec(where)
    rows = None if "rows" in {f.name for f in dataclasses.fields(spec.params)} else params.pop("rows", None)
    values = spec.params.from_overrides(**params)
    changes: dict[str, Any] = {} if actuated is None else {"actuated": tuple(actuated)}
    if home is not None:
        changes["home"] = _constant(dict(home))
    if guess is not None:
        changes["guess"] = _constant(dict(guess))
    return from_params(dataclasses.replace(spec, **changes) if changes else spec, values, rows)


def _constant(value: dict[str, float]) -> Callable[[Any], dict[str, float]]:
    return lambda params: dict(value)


def from_params(spec: MechanismSpec, params: MechanismParams, rows: str | None = None) -> Mechanism:
    """Build a mechanism from a parameter instance: its template expanded, the tree and its loops read.

    Args:
        spec: the registry entry (its template and actuated joints).
        params: the parameter values the template is expanded at.
        rows: "spatial" closes every cut with its full rows (None: the rows the loops declare).

    Returns:
        The assembled mechanism.

    Raises:
        MalformedDescription: the expanded URDF is invalid.
        InvalidParameters: an unknown actuated joint.
    """
    return from_expanded(spec, params, render_urdf(spec.template_path, params.xacro_args()), rows)


def from_expanded(spec: MechanismSpec, params: MechanismParams, urdf: str, rows: str | None = None) -> Mechanism:
    """Build a registered mechanism from its template already expanded at `params` (e.g. by a sweep's cache).

    Args:
        spec: the registry entry (its actuated joints).
        params: the parameter values the template was expanded at.
        urdf: the expanded URDF text (tree and `<mechkit:loop>`s).
        rows: "spatial" closes every cut with its full rows (None: the rows the loops declare).

    Returns:
        The assembled mechanism.

    Raises:
        MalformedDescription: the URDF is invalid.
        InvalidParameters: an unknown actuated joint.
    """
    root = parse_xml(urdf)
    model = build_model(urdf)
    cm = core.ClosureModel(model, parse_loops(root), actuated=spec.actuated_joints(params), rows=rows)
    return Mechanism(spec, params, cm, urdf, parse_springs(root))


def from_description(
    desc: sources.Description,
    actuated: Sequence[str] | None = None,
    home: Mapping[str, float] | None = None,
    guess: Mapping[str, float] | None = None,
    rows: str | None = None,
) -> Mechanism:
    """Build a mechanism from what a file reader gave.

    Its spec's `gruebler_dof` is the Kutzbach count of its topology (`mechkit.core.structure`).

    Args:
        desc: the file's description (`mechkit.sources.Description`).
        actuated: actuated joints, overriding the file's (see `load`).
        home: joint -> value (rad or m) of the home assembly's inputs (default: the file's).
        guess: joint -> value near which the home assembly is sought (default: the file's).
        rows: "spatial" closes every cut with its full rows (None: the rows the file declares).

    Returns:
        The assembled mechanism, named after the file.

    Raises:
        InvalidArgument: `home` or `guess` not a mapping.
    """
    for arg, value in (("home", home), ("guess", guess)):
        if value is not None and not isinstance(value, Mapping):
            raise InvalidArgument(arg, value, "expected a mapping joint name -> value")
    model = desc.model if desc.model is not None else build_model(desc.urdf)
    check_model(model)
    if actuated is not None:
        transmissions = actuator_names.transmission_names(desc.urdf)  # a <transmission> by its name
        known = list(model.names[1:]) + [a.name for a in desc.actuators] + list(transmissions)
        joint_arguments.joint_names("actuated", actuated, known, allow_empty=True)
        actuated = [transmissions.get(a, a) for a in actuated]
    closures = desc.closures if desc.closures is not None else parse_loops(desc.urdf)
    cm = core.ClosureModel(
        model,
        closures,
        desc.couplings,
        tuple(actuated) if actuated is not None else desc.actuated,
        desc.actuators,
        rows,
    )
    home_values = dict(home) if home is not None else dict(desc.home)
    guess_values = dict(guess) if guess is not None else dict(desc.guess)
    where = f" {desc.source}" if desc.source is not None else ""
    params = _xacro_params(desc)
    spec = MechanismSpec(
        name=desc.name,
        params=type(params),
        template="",
        actuated=cm.actuated,
        gruebler_dof=cm.structure.kutzbach,
        home=_constant(home_values),
        guess=_constant(guess_values) if guess_values else None,
        pose="the guess given" if guess is not None else desc.pose,
        summary=f"read from the {desc.format} file{where}",
    )
    return Mechanism(spec, params, cm, desc.urdf, desc.springs, desc.source_urdf)


def _xacro_params(desc: sources.Description) -> MechanismParams:
    """The file's xacro arguments as a parameter instance (strings; shown by `report`), else none."""
    fields = [
        (k, str, dataclasses.field(default=v, metadata={"unit": "-", "doc": "xacro argument", "ours": False}))
        for k, v in desc.params.items()
    ]
    cls = dataclasses.make_dataclass("XacroArguments", fields, bases=(MechanismParams,), frozen=True)
    return cls()


def from_urdf(
    urdf: str | Path,
    actuated: Sequence[str] | None = None,
    name: str | None = None,
    guess: Mapping[str, float] | None = None,
    home: Mapping[str, float] | None = None,
    rows: str | None = None,
) -> Mechanism:
    """Wrap a URDF (text, or a path to any description file) as a Mechanism.

    Args:
        urdf: URDF text (a tree, or with `<mechkit:loop>` closures), or a path (see `load`).
        actuated: actuated joint names (default: the URDF's `<transmission>` joints; none declared
            makes the mechanism unactuated).
        name: a name for reports (default: the robot's name).
        guess: see `load`.
        home: see `load`.
        rows: see `load`.

    Returns:
        The assembled mechanism.

    Raises:
        InvalidArgument: `urdf` neither non-empty text nor a path.
    """
    if not isinstance(urdf, (str, Path)) or not str(urdf).strip():
        raise InvalidArgument("urdf", urdf, "expected URDF text or a path to a description file")
    if isinstance(urdf, Path) or not urdf.lstrip().startswith("<"):
        desc = sources.read(resolve(Path(urdf)))
    else:
        desc = sources.describe_urdf(urdf, None, "urdf")
    if name is not None:
        desc = dataclasses.replace(desc, name=name)
    return from_description(desc, actuated, home, guess, rows)
