"""The bad-input suite's dem cases (tests/bad_inputs.py): each ends in its exception, naming the problem."""
import pytest

from bad_inputs import assert_clear, cases


@pytest.mark.parametrize("case", cases("dem"), ids=lambda c: c.name)
def test_bad_input_is_refused_by_name(case, tmp_path):
    assert_clear(case, tmp_path)
