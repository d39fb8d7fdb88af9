"""The fast load path renders exactly the URDF xacro renders, over random parameter sets."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import MalformedDescription
from mechkit.catalog.registry import get_spec, names
from mechkit.sources.template_cache import TemplateCache
from mechkit.sources.xacro_file import render_urdf


def _random_args(args: dict[str, str], floats: tuple[str, ...], rng: np.random.Generator) -> dict[str, str]:
    return {
        k: repr(float(v) * (1 + 0.05 * rng.standard_normal()) + 1e-3 * rng.standard_normal()) if k in floats else v
        for k, v in args.items()
    }


@pytest.mark.parametrize("name", names())
def test_substitution_equals_xacro(name):
    spec = get_spec(name)
    cache = TemplateCache(spec.template_path)
    args = spec.params().xacro_args()
    floats = cache.structure_key(args)[0]
    assert floats, "every template has float arguments"
    if name in ("four_bar", "ten_bar", "deployable_9rr12uru"):
        assert cache.traceable(args)  # the sweep's fast path, not the fallback
    rng = np.random.default_rng(sum(map(ord, name)))
    compared = 0
    for _ in range(3):
        probe = _random_args(args, floats, rng)
        try:
            expected = render_urdf(spec.template_path, probe)
        except MalformedDescription:  # e.g. asin of a ratio > 1: the cache must fail the same way
            with pytest.raises(MalformedDescription):
                cache.render(probe)
            continue
        assert cache.render(probe) == expected
        compared += 1
    assert compared >= 2


def test_untraceable_template_falls_back_to_xacro(tmp_path):
    template = tmp_path / "t.urdf.xacro"
    template.write_text(
        '<?xml version="1.0"?>\n<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="a" default="1.0"/>\n'
        '  <xacro:property name="a" value="$(arg a)"/>\n'
        '  <link name="l${2 * a}"/>\n'
        '  <xacro:if value="${a > 1.5}"><link name="big"/></xacro:if>\n</robot>\n'
    )
    cache = TemplateCache(template)
    assert not cache.traceable({"a": "1.0"})  # the comparison depends on the value
    for a in ("1.0", "2.0"):
        assert cache.render({"a": a}) == render_urdf(template, {"a": a})
    assert "big" in cache.render({"a": "2.0"})
