"""exemplar.stylize and exemplar.apply_nnf: the same results as the library through the CLI,
keywords that mean what the CLI's flags mean, arrays in and out."""

import subprocess

import numpy as np
import pytest

import exemplar


def test_same_bytes_as_the_cli_for_the_same_seed(pair, cli, tmp_path):
    style, source, target = pair
    for name, image in (("style", style), ("a", source), ("b", target)):
        exemplar.save_image(image, str(tmp_path / f"{name}.png"))
    out, nnf = tmp_path / "out.png", tmp_path / "nnf.exr"
    subprocess.run([cli, "stylize", "--style", str(tmp_path / "style.png"),
                    "--guide", str(tmp_path / "a.png"), str(tmp_path / "b.png"), "--weight", "2",
                    "--seed", "7", "--usage", "uniform", "-j", "2", "-q", "-o", str(out),
                    "--save-nnf", str(nnf)], check=True)

    result = exemplar.stylize(style, [(source, target, 2.0)], seed=7, usage="uniform", threads=1)

    assert result.image.dtype == np.uint8
    assert result.image.shape == (26, 32, 3)
    from_cli = np.round(exemplar.load_image(str(out)) * 255).astype(np.uint8)
    np.testing.assert_array_equal(result.image, from_cli)
    np.testing.assert_array_equal(result.nnf, exemplar.load_image(str(nnf)))


def test_a_float32_run_is_the_uint8_run_before_rounding(pair):
    style, source, target = pair
    as_float = [(image.astype(np.float32) / np.float32(255)) for image in pair]
    bytes_result = exemplar.stylize(style, [(source, target)], seed=3)
    float_result = exemplar.stylize(as_float[0], [(as_float[1], as_float[2])], seed=3)
    assert float_result.image.dtype == np.float32
    rounded = np.round(np.clip(float_result.image, 0, 1).astype(np.float64) * 255)
    np.testing.assert_array_equal(rounded.astype(np.uint8), bytes_result.image)
    np.testing.assert_array_equal(float_result.nnf, bytes_result.nnf)


def test_the_result_does_not_depend_on_the_thread_count(pair):
    style, source, target = pair
    one = exemplar.stylize(style, [(source, target)], threads=1)
    two = exemplar.stylize(style, [(source, target)], threads=2)
    np.testing.assert_array_equal(one.image, two.image)
    np.testing.assert_array_equal(one.nnf, two.nnf)


def test_the_seed_changes_the_result(pair):
    style, source, target = pair
    first = exemplar.stylize(style, [(source, target)], seed=1)
    second = exemplar.stylize(style, [(source, target)], seed=2)
    assert not np.array_equal(first.nnf, second.nnf)


def test_a_quality_preset_is_its_options_and_explicit_options_override_it(pair):
    style, source, target = pair
    fast = exemplar.stylize(style, [(source, target)], quality="fast")
    spelled_out = exemplar.stylize(style, [(source, target)], finest_em_iterations=1,
                                   second_finest_em_iterations=1, warm_search_iterations=1,
                                   budget_polish_iterations=1, em_iterations=3,
                                   budget_max_rounds=1, finest_search_radius=8,
                                   budget_polish_levels=3)
    default = exemplar.stylize(style, [(source, target)])
    # fast's options back at the default preset's values (and the default's own change fast
    # does not make, the coherence of the votes).
    overridden = exemplar.stylize(style, [(source, target)], quality="fast",
                                  finest_em_iterations=1, second_finest_em_iterations=4,
                                  warm_search_iterations=2, budget_polish_iterations=0,
                                  em_iterations=6, budget_max_rounds=32, finest_search_radius=0,
                                  budget_polish_levels=2, vote_coherence=2)
    np.testing.assert_array_equal(fast.nnf, spelled_out.nnf)
    assert not np.array_equal(fast.nnf, default.nnf)
    np.testing.assert_array_equal(overridden.nnf, default.nnf)


def test_guides_as_dicts_and_tuples_are_the_same(pair):
    style, source, target = pair
    weight_map = np.full(target.shape[:2], 0.5, dtype=np.float32)
    as_tuple = exemplar.stylize(style, [(source, target, 2.0, weight_map)])
    guides = [{"source": source, "target": target, "weight": 2.0, "weight_map": weight_map}]
    as_dict = exemplar.stylize(style, guides)
    np.testing.assert_array_equal(as_tuple.image, as_dict.image)
    np.testing.assert_array_equal(as_tuple.nnf, as_dict.nnf)
    # The caller's dicts are read, not emptied: the same list gives the same result again.
    assert sorted(guides[0]) == ["source", "target", "weight", "weight_map"]
    np.testing.assert_array_equal(exemplar.stylize(style, guides).image, as_dict.image)


def test_the_result_describes_its_field(pair):
    style, source, target = pair
    result = exemplar.stylize(style, [(source, target)], final_pass_iterations=1)
    assert result.nnf.shape == (26, 32, 4) and result.nnf.dtype == np.float32
    assert result.error.shape == (26, 32) and result.error.dtype == np.float32
    assert result.nnf_patch_size == 3 and result.vote_size == 3
    x, y = result.nnf[..., 0], result.nnf[..., 1]
    assert (x >= 0).all() and (x < 28).all() and (y >= 0).all() and (y < 24).all()
    assert result.guide_channels == 1 and result.explained_variance == 1.0
    assert "StylizeResult" in repr(result)


def test_apply_nnf_reproduces_the_image(pair):
    style, source, target = pair
    style_float = style.astype(np.float32) / np.float32(255)
    result = exemplar.stylize(style_float, [(source, target)])
    again = exemplar.apply_nnf(result.nnf, style_float, patch_size=result.nnf_patch_size,
                               vote_size=result.vote_size, vote_coherence=result.vote_coherence,
                               vote_seams=result.vote_seams)
    np.testing.assert_array_equal(again, result.image)
    # The field applies to any image on the style's grid, e.g. more channels.
    extra = exemplar.apply_nnf(result.nnf, np.dstack([style_float, style_float[..., :1]]),
                               patch_size=result.nnf_patch_size, vote_size=result.vote_size,
                               vote_coherence=result.vote_coherence, vote_seams=result.vote_seams)
    assert extra.shape == (26, 32, 4)
    np.testing.assert_array_equal(extra[..., :3], result.image)
    as_bytes = exemplar.apply_nnf(result.nnf, style, patch_size=5)
    assert as_bytes.dtype == np.uint8
    # The default preset weighs coherence and blends its seams (passed above); a run that does
    # not blend them is reproduced without vote_seams, and quality best with both.
    assert result.vote_seams
    assert result.vote_coherence == 2.0
    narrow = exemplar.stylize(style_float, [(source, target)], final_vote_seams=0)
    assert not narrow.vote_seams
    again = exemplar.apply_nnf(narrow.nnf, style_float, patch_size=narrow.nnf_patch_size,
                               vote_size=narrow.vote_size, vote_coherence=narrow.vote_coherence)
    np.testing.assert_array_equal(again, narrow.image)
    best = exemplar.stylize(style_float, [(source, target)], quality="best")
    assert best.vote_seams
    assert best.vote_coherence == 2.0
    again = exemplar.apply_nnf(best.nnf, style_float, patch_size=best.nnf_patch_size,
                               vote_size=best.vote_size, vote_seams=best.vote_seams,
                               vote_coherence=best.vote_coherence)
    np.testing.assert_array_equal(again, best.image)


def test_unguided_texture_synthesis_takes_a_size(pair):
    style = pair[0]
    result = exemplar.stylize(style, size=(40, 30))
    assert result.image.shape == (30, 40, 3)


def test_a_target_mask_keeps_the_initial_target_outside(pair):
    style, source, target = pair
    init = np.zeros((26, 32, 3), dtype=np.uint8)
    mask = np.zeros((26, 32), dtype=np.uint8)
    mask[8:18, 10:22] = 255
    result = exemplar.stylize(style, [(source, target)], init=init, target_mask=mask)
    assert (result.image[mask == 0] == 0).all()
    assert (result.image[mask == 255] != 0).any()


def test_labels_restrict_the_patches(pair):
    style, source, target = pair
    source_labels = np.zeros((24, 28), dtype=np.uint8)
    source_labels[:, 14:] = 1
    target_labels = np.ones((26, 32), dtype=np.uint8)
    result = exemplar.stylize(style, [(source, target)], source_labels=source_labels,
                              target_labels=target_labels)
    # Every centre comes from label 1, whose patches lie entirely in x >= 14.
    assert (result.nnf[..., 0] >= 14).all()


def test_the_result_names_the_levels_where_labels_could_not_hold(pair):
    style, source, target = pair
    # Label 1 on the two right columns, behind a masked-out column: no valid patch of label 1 on
    # the finest level, so the labels are dropped there and the result says so.
    source_labels = np.zeros((24, 28), dtype=np.uint8)
    source_labels[:, 26:] = 1
    source_mask = np.full((24, 28), 255, dtype=np.uint8)
    source_mask[:, 25] = 0
    target_labels = np.zeros((26, 32), dtype=np.uint8)
    target_labels[:13] = 1
    result = exemplar.stylize(style, [(source, target)], source_labels=source_labels,
                              target_labels=target_labels, source_mask=source_mask)
    assert 0 in result.unlabelled_levels
    wide = np.zeros((24, 28), dtype=np.uint8)
    wide[:, 14:] = 1
    assert exemplar.stylize(style, [(source, target)], source_labels=wide,
                            target_labels=target_labels).unlabelled_levels.count(0) == 0


def test_the_output_array_owns_its_memory_safely(pair):
    style, source, target = pair
    image = exemplar.stylize(style.astype(np.float32), [(source, target)]).image
    # The result's buffer outlives the result object (the array holds the image).
    copy = image.copy()
    del style
    np.testing.assert_array_equal(image, copy)
    assert image.flags.c_contiguous and image.flags.writeable
