"""Bad input from Python: a clear exception with the library's one-line message (or, for what
only Python can get wrong, one naming the argument), never a crash."""

import re

import numpy as np
import pytest

import exemplar


def raises(kind, message):
    return pytest.raises(kind, match="^" + re.escape(message) + "$")


def test_the_exception_classes_fit_pythons():
    assert issubclass(exemplar.InvalidArgumentError, exemplar.Error)
    assert issubclass(exemplar.InvalidArgumentError, ValueError)
    assert issubclass(exemplar.UnsupportedError, ValueError)
    assert issubclass(exemplar.IoError, OSError)
    assert issubclass(exemplar.InternalError, RuntimeError)
    assert issubclass(exemplar.Cancelled, exemplar.Error)
    assert exemplar.Error.__module__ == "exemplar"


def test_option_values_out_of_range_raise_the_librarys_message(pair):
    style, source, target = pair
    guides = [(source, target)]
    with raises(exemplar.InvalidArgumentError, "patch-size: 4 is invalid (must be odd, 3..31)"):
        exemplar.stylize(style, guides, patch_size=4)
    with pytest.raises(ValueError, match="^pyramid-ratio: 0.1 is invalid"):
        exemplar.stylize(style, guides, pyramid_ratio=0.1)
    with pytest.raises(ValueError, match="^em-iterations: 2.5 is invalid"):
        exemplar.stylize(style, guides, em_iterations=2.5)
    with pytest.raises(ValueError, match="^quality: 'superb' is invalid"):
        exemplar.stylize(style, guides, quality="superb")
    with pytest.raises(ValueError, match="usage"):
        exemplar.stylize(style, guides, usage="sometimes")
    with pytest.raises(ValueError, match="vote"):
        exemplar.stylize(style, guides, vote="majority")
    with raises(exemplar.InvalidArgumentError,
                "threads: -1 is invalid (must be >= 0; 0 = all cores)"):
        exemplar.stylize(style, guides, threads=-1)


def test_wrong_keyword_names_and_types_raise_type_errors(pair):
    style, source, target = pair
    with raises(TypeError, "stylize() got an unexpected keyword argument 'patchsize'"):
        exemplar.stylize(style, [(source, target)], patchsize=5)
    with raises(TypeError, "patch_size: must be a number (got str)"):
        exemplar.stylize(style, [(source, target)], patch_size="5")
    with raises(TypeError, "patch_size: must be a number (got bool)"):
        exemplar.stylize(style, [(source, target)], patch_size=True)
    with raises(TypeError, "usage: must be a str (got int)"):
        exemplar.stylize(style, [(source, target)], usage=1)
    with raises(TypeError, "progress: must be callable (got int)"):
        exemplar.stylize(style, [(source, target)], progress=1)
    # numpy scalars are numbers.
    exemplar.stylize(style, [(source, target)], patch_size=np.int64(3), seed=np.uint64(2))


def test_wrong_dtypes_are_refused(pair):
    style, source, target = pair
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^style: dtype float64 is not supported \(must be float32 or uint8"):
        exemplar.stylize(style.astype(np.float64), [(source, target)])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^guides\[0\] target: dtype int32"):
        exemplar.stylize(style, [(source, target.astype(np.int32))])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^style: must be a numpy array"):
        exemplar.stylize(style.tolist(), [(source, target)])


def test_wrong_shapes_are_refused(pair):
    style, source, target = pair
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^style: has shape \(24, 28\) \(must be HxWxC"):
        exemplar.stylize(style[..., 0], [(source, target)])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^guides\[0\] source: has shape"):
        exemplar.stylize(style, [(source[None], target)])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^style: is empty"):
        exemplar.stylize(style[:0], [(source, target)])
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^target_mask: has shape \(26, 32, 3\) \(must be HxW or HxWx1"):
        exemplar.stylize(style, [(source, target)], init=np.zeros((26, 32, 3), np.uint8),
                         target_mask=np.zeros((26, 32, 3), np.uint8))


def test_non_contiguous_arrays_are_refused(pair):
    style, source, target = pair
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^style: is not C-contiguous .*numpy.ascontiguousarray\(style\)"):
        exemplar.stylize(style[:, ::2], [(source[:, ::2], target)])
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^guides\[0\] source: is not C-contiguous"):
        exemplar.stylize(style, [(np.asfortranarray(source), target)])


def test_mismatched_sizes_and_channels_raise_the_librarys_message(pair):
    style, source, target = pair
    with raises(exemplar.InvalidArgumentError,
                "guide 1: source guide is 27x24 but the style is 28x24"):
        exemplar.stylize(style, [(np.ascontiguousarray(source[:, 1:]), target)])
    with raises(exemplar.InvalidArgumentError,
                "guide 2: target guide is 31x26 but the first target guide is 32x26"):
        exemplar.stylize(style, [(source, target),
                                 (source, np.ascontiguousarray(target[:, 1:]))])
    with raises(exemplar.InvalidArgumentError,
                "guide 1: source guide has 3 channels but the target guide has 1"):
        exemplar.stylize(style, [(np.repeat(source, 3, axis=2), target)])
    with raises(exemplar.InvalidArgumentError, "style: contains NaN or infinity"):
        bad = style.astype(np.float32)
        bad[3, 4, 1] = np.nan
        exemplar.stylize(bad, [(source, target)])
    with pytest.raises(exemplar.InvalidArgumentError, match="^style-weights: 2 values given"):
        exemplar.stylize(style, [(source, target)], style_weights=[1, 2])


def test_malformed_guides_raise_type_errors(pair):
    style, source, target = pair
    with pytest.raises(TypeError, match=r"^guides: must be a sequence"):
        exemplar.stylize(style, source)
    with pytest.raises(TypeError, match=r"^guides\[0\]: must be \(source, target"):
        exemplar.stylize(style, [(source,)])
    with pytest.raises(TypeError, match=r"^guides\[0\]: unknown key 'wieght'"):
        exemplar.stylize(style, [{"source": source, "target": target, "wieght": 1}])


def test_inputs_that_need_a_partner_say_so(pair):
    style, source, target = pair
    with raises(exemplar.InvalidArgumentError,
                "source_labels: needs target_labels too (give both label maps, or neither)"):
        exemplar.stylize(style, [(source, target)], source_labels=np.zeros((24, 28), np.uint8))
    with pytest.raises(exemplar.InvalidArgumentError,
                       match="^target labels: value 2 does not occur"):
        exemplar.stylize(style, [(source, target)],
                         source_labels=np.zeros((24, 28), np.float32),
                         target_labels=np.full((26, 32), 2, np.float32))
    with pytest.raises(exemplar.InvalidArgumentError,
                       match="^source_orientation: an orientation field holds angles in radians"):
        exemplar.stylize(style, [(source, target)], source_orientation=source[..., 0],
                         target_orientation=target[..., 0])
    with pytest.raises(exemplar.InvalidArgumentError, match="^target size: unknown"):
        exemplar.stylize(style)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^size: \(40, 30\) but the target"):
        exemplar.stylize(style, [(source, target)], size=(40, 30))


def test_apply_nnf_checks_its_inputs(pair):
    style = pair[0]
    field = np.zeros((10, 12, 4), np.float32)
    with raises(TypeError, "apply_nnf() missing required keyword argument 'patch_size' (the "
                           "result's nnf_patch_size)"):
        exemplar.apply_nnf(field, style)
    with raises(exemplar.InvalidArgumentError, "patch-size: 4 is invalid (must be odd, 3..31)"):
        exemplar.apply_nnf(field, style, patch_size=4)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^vote_size: 2 is invalid"):
        exemplar.apply_nnf(field, style, patch_size=5, vote_size=2)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^nnf: must be float32"):
        exemplar.apply_nnf(field.astype(np.uint8), style, patch_size=5)
    outside = field.copy()
    outside[..., 0] = 100
    with pytest.raises(exemplar.InvalidArgumentError):
        exemplar.apply_nnf(outside, style, patch_size=5)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^nnf: "):
        exemplar.apply_nnf(np.full((10, 12, 4), 0.5, np.float32), style, patch_size=5)


def test_io_errors_name_the_file(tmp_path):
    missing = str(tmp_path / "missing.png")
    with pytest.raises(exemplar.IoError, match=re.escape(missing)):
        exemplar.load_image(missing)
    with pytest.raises(OSError):
        exemplar.load_image(missing)
    with pytest.raises(exemplar.UnsupportedError, match="PNG cannot store 5 channels"):
        exemplar.save_image(np.zeros((4, 4, 5), np.uint8), str(tmp_path / "five.png"))


def test_wrongly_typed_run_keywords_raise_type_errors(pair):
    style, source, target = pair
    guides = [(source, target)]
    with raises(TypeError, "threads: must be an int (got str)"):
        exemplar.stylize(style, guides, threads="2")
    with raises(TypeError, "threads: must be an int (got float)"):
        exemplar.apply_nnf(np.zeros((4, 4, 4), np.float32), style, patch_size=3, threads=1.5)
    with raises(TypeError, "size: must be (width, height)"):
        exemplar.stylize(style, size=40)
    with raises(TypeError, "size: must be an int (got float)"):
        exemplar.stylize(style, size=(40.0, 30))
    with raises(TypeError, "vote: must be a str (got int)"):
        exemplar.apply_nnf(np.zeros((4, 4, 4), np.float32), style, patch_size=3, vote=1)
    with raises(TypeError, "preset: must be a str (got int)"):
        exemplar.stylit(style, [source], [target], preset=3)
    with raises(TypeError, "cancel: must be an exemplar.CancelToken (got bool)"):
        exemplar.stylize(style, guides, cancel=True)


def test_nnf_errors_name_the_argument_once(pair):
    style = pair[0]
    with raises(exemplar.InvalidArgumentError,
                "nnf: has 2 channels (must be 3 or 4: x, y, angle[, error])"):
        exemplar.apply_nnf(np.zeros((5, 5, 2), np.float32), style, patch_size=3)
    with raises(exemplar.InvalidArgumentError,
                "init_nnf: has 2 channels (must be 3 or 4: x, y, angle[, error])"):
        exemplar.stylize(style, size=(9, 9), init_nnf=np.zeros((9, 9, 2), np.float32))
