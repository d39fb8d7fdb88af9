"""`mechkit.cli.option_values`: every option value parsed in one place, every refusal naming the option as
typed, the token that failed and the form expected; a name given twice refused."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import InvalidArgument
from mechkit.cli import option_values as ov


def _refused(call, *words):
    with pytest.raises(InvalidArgument) as err:
        call()
    for word in words:
        assert word in str(err.value), str(err.value)


def test_pairs():
    assert ov.pairs("--set", ["a=1", " b = x=y "]) == {"a": "1", "b": "x=y"}
    assert ov.pairs("--set", ["prefix="], empty=True) == {"prefix": ""}
    assert ov.pairs("--set", None) == {}
    _refused(lambda: ov.pairs("--set", ["a"]), "'--set'", "expected NAME=VALUE", "'a'")
    _refused(lambda: ov.pairs("--set", ["=1"]), "expected NAME=VALUE")
    _refused(lambda: ov.pairs("--set", ["a="]), "expected NAME=VALUE")
    _refused(lambda: ov.pairs("--set", ["a=1", "a=2"]), "'a' is given twice ('1' and '2')")


def test_names():
    assert ov.names("--actuated", " crank , rocker") == ["crank", "rocker"]
    _refused(lambda: ov.names("--keep", "a,,b"), "'--keep'", "none empty")
    _refused(lambda: ov.names("--joints", "a,b,a"), "'a' given twice")


def test_numbers():
    assert ov.numbers("--gravity", "0,0,-9.81", 3) == [0.0, 0.0, -9.81]
    assert ov.numbers("--spring", "1,2", (2, 3)) == [1.0, 2.0]
    _refused(lambda: ov.numbers("--gravity", "0,x,1", 3), "'--gravity'", "'x' is not a number")
    _refused(lambda: ov.numbers("--point", "0,nan,1", 3), "'nan' is not finite")
    _refused(lambda: ov.numbers("--point", "0,inf,1", 3), "'inf' is not finite")
    _refused(lambda: ov.numbers("--friction", "0.1", 2, what="MU,RADIUS"), "expected MU,RADIUS: 1 number(s) given")
    _refused(lambda: ov.numbers("--q", ""), "'' is not a number")


def test_named_numbers_show_the_pair_as_typed():
    assert ov.named_numbers("--lock", ["ball=0.1,0.2,0.3", "crank=1"]) == {"ball": [0.1, 0.2, 0.3], "crank": [1.0]}
    _refused(
        lambda: ov.named_numbers("--latch", ["crank=abc"], "JOINT=VALUE", 1), "'abc' is not a number", "'crank=abc'"
    )
    _refused(lambda: ov.named_numbers("--latch", ["crank=1,2"], "JOINT=VALUE", 1), "2 number(s) given")
    _refused(lambda: ov.named_numbers("--latch", ["crank"], "JOINT=VALUE", 1), "expected JOINT=VALUE")


def test_suffixed():
    assert ov.suffixed("--plot", "a.PNG", (".png", ".svg")) == "a.PNG"
    assert ov.suffixed("--plot", None, (".png",)) is None
    _refused(lambda: ov.suffixed("--plot", "a.xyz", (".png", ".svg")), "'--plot'", "expected a .png or .svg file")


def test_an_argument_is_named_as_typed_where_the_command_has_that_option():
    """ "parameter 'lock'" named the library's keyword; the command line names its option."""
    from mechkit.base.exceptions import InvalidParameters

    err = InvalidParameters("lock", ["nope"], "'nope' is not a joint")
    assert ov.as_typed(err, {"--lock", "-o"}) == "--lock: 'nope' is not a joint (got ['nope'])"
    assert ov.as_typed(err, {"-o"}) == str(err)  # not an option of that command: as it is
    assert ov.as_typed(InvalidParameters("ground", 2.0, "too long"), {"--lock"}).startswith("parameter 'ground'")
