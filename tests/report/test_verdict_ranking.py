"""The verdict's ranking logic on synthetic numbers (src/report/verdict_ranking.py):
ordering, ties within the seeds' spread, the equal-time definition, ratios
across scenes and the paragraph."""

import math
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "src", "report"))
import verdict_ranking as vr  # noqa: E402


def ranked_names(entries):
    return [(e.name, e.rank, e.tied) for e in vr.rank(entries)]


def test_lower_error_ranks_first_and_separated_intervals_are_not_tied():
    entries = [vr.Entry("b", [2.0, 2.1, 2.2]), vr.Entry("a", [1.0, 1.1, 1.2]),
               vr.Entry("c", [3.0, 3.1, 3.2])]
    assert ranked_names(entries) == [("a", 1, False), ("b", 2, False), ("c", 3, False)]


def test_overlapping_seed_ranges_share_a_rank():
    # a and b overlap; c overlaps b but lies wholly above a, so only a beats it.
    entries = [vr.Entry("a", [1.0, 2.0]), vr.Entry("b", [1.5, 3.0]), vr.Entry("c", [2.5, 4.0])]
    assert ranked_names(entries) == [("a", 1, True), ("b", 1, True), ("c", 2, False)]


def test_a_sampler_the_seed_does_not_change_ties_only_where_it_falls_inside():
    # One value over all seeds (an unscrambled sampler) is a point interval.
    entries = [vr.Entry("fixed", [1.5, 1.5, 1.5]), vr.Entry("random", [1.0, 1.4, 2.0]),
               vr.Entry("worse", [1.6, 1.7])]
    # Shared ranks are listed by their means: random's 1.47 before fixed's 1.5.
    assert ranked_names(entries) == [("random", 1, True), ("fixed", 1, True),
                                     ("worse", 2, False)]


def test_missing_and_non_finite_values_are_left_out():
    entries = [vr.Entry("a", [1.0, float("nan")]), vr.Entry("none", [None, None])]
    ranked = vr.rank(entries)
    assert [e.name for e in ranked] == ["a"]
    assert ranked[0].mean == 1.0


def test_equal_time_error_is_mse_times_seconds_per_seed():
    assert vr.equal_time_values([0.5, 0.25, 1.0], [2.0, 4.0, 0.0]) == [1.0, 1.0, None]
    # Twice the error in half the time is the same equal-time error: a tie.
    fast = vr.Entry("fast", vr.equal_time_values([2.0, 2.2], [0.5, 0.5]))
    slow = vr.Entry("slow", vr.equal_time_values([1.0, 1.1], [1.0, 1.0]))
    assert [e.rank for e in vr.rank([fast, slow])] == [1, 1]
    # By MSE alone the slow one wins clearly.
    by_mse = vr.rank([vr.Entry("fast", [2.0, 2.2]), vr.Entry("slow", [1.0, 1.1])])
    assert [(e.name, e.rank) for e in by_mse] == [("slow", 1), ("fast", 2)]


def test_across_scenes_is_the_geometric_mean_of_ratios_to_the_baseline():
    per_scene = {
        "one": {"base": {0: 4.0, 1: 4.0}, "good": {0: 1.0, 1: 1.0}},
        "two": {"base": {0: 1.0, 1: 1.0}, "good": {0: 1.0, 1: 1.0}},
    }
    entries = {e.name: e for e in vr.across_scenes(per_scene, "base")}
    assert entries["base"].mean == pytest.approx(1.0)
    # ratios 1/4 and 1: geometric mean 1/2 (an arithmetic mean would say 5/8).
    assert entries["good"].mean == pytest.approx(0.5)
    assert entries["good"].lo == pytest.approx(0.5) and entries["good"].hi == pytest.approx(0.5)


def test_across_scenes_interval_comes_from_each_seeds_ratios():
    per_scene = {"one": {"base": {0: 2.0, 1: 2.0}, "s": {0: 1.0, 1: 3.0}}}
    e = {x.name: x for x in vr.across_scenes(per_scene, "base")}["s"]
    assert e.mean == pytest.approx(1.0)
    assert (e.lo, e.hi) == (pytest.approx(0.5), pytest.approx(1.5))


def test_across_scenes_takes_only_samplers_every_scene_has():
    per_scene = {"one": {"base": {0: 1.0}, "both": {0: 1.0}, "only": {0: 0.1}},
                 "two": {"base": {0: 1.0}, "both": {0: 2.0}}}
    assert sorted(e.name for e in vr.across_scenes(per_scene, "base")) == ["base", "both"]
    assert vr.across_scenes({"one": {"x": {0: 1.0}}}, "base") == []


def test_geometric_mean():
    assert vr.geometric_mean([2.0, 8.0]) == pytest.approx(4.0)
    assert vr.geometric_mean([]) is None
    assert vr.geometric_mean([1.0, 0.0]) is None


def test_focus_spp_prefers_16_else_the_middle():
    assert vr.focus_spp([1, 4, 16, 64]) == 16
    assert vr.focus_spp([1, 2, 4, 8, 32]) == 4
    assert vr.focus_spp([]) is None


def test_paragraph_names_leaders_ties_and_groups_from_the_data():
    overall = {"mse": vr.rank([vr.Entry("sobol-owen", [0.4, 0.42]),
                               vr.Entry("independent", [1.0, 1.0])]),
               "flip": vr.rank([vr.Entry("zsobol", [0.8, 0.9]),
                                vr.Entry("sobol-owen", [0.85, 0.95])]),
               "equal_time": vr.rank([vr.Entry("independent", [0.9, 1.0]),
                                      vr.Entry("sobol-owen", [1.2, 1.3])])}
    env = vr.rank([vr.Entry("halton-owen", [0.3]), vr.Entry("independent", [1.0])])
    text = vr.verdict_paragraph(16, "independent", 4, overall, [("environment", ["envmap-sun"], env)],
                                (64, vr.rank([vr.Entry("zsobol", [0.2])])))
    assert text.startswith("At 16 spp, across the 4 scenes, the lowest MSE is sobol-owen (0.41×)")
    assert "By ꟻLIP it is zsobol and sobol-owen, tied" in text
    assert "by equal time (MSE × time) it is independent (0.95×)" in text
    assert "on environment-lit scenes (envmap-sun), halton-owen (0.30×)" in text
    assert "At 64 spp the lowest MSE is zsobol (0.20×)" in text
    # Other numbers give another answer: nothing is fixed text.
    overall["mse"] = vr.rank([vr.Entry("independent", [0.5]), vr.Entry("sobol-owen", [0.9])])
    other = vr.verdict_paragraph(16, "independent", 4, overall, [], None)
    assert "the lowest MSE is independent (0.50×)" in other
    assert math.isclose(overall["mse"][0].mean, 0.5)
