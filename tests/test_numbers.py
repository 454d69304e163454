"""The comparison of printed output used by the README and CLI tests: a last
digit of round-off passes, a real change of a number or of the text does not."""

from tests.numbers import assert_lines_match, assert_rows_match, text_matches

#: The line of the README's simulate example as printed on the machine that wrote it, and as a
#: fresh clone on another CPU printed it (the suite failed there).
HERE = "0.01,0.50000063346,0.500000393517,-0.000489839441738"
THERE = "0.01,0.50000063346,0.500000393517,-0.000489839441739"


def test_round_off_in_the_last_digit_passes():
    assert text_matches(THERE, HERE)
    assert_lines_match(["t,AB,tip_x,tip_y", THERE], ["t,AB,tip_x,tip_y", HERE])
    assert text_matches("  tip_y        -3.27479308e-06", "  tip_y        -3.27479307e-06")
    assert text_matches("  phi          1e-19", "  phi          0")  # zero at round-off level


def test_a_value_rounded_across_a_printed_digit_passes():
    """1.9818325 Hz computed with one BLAS thread or two prints as 1.981832 or 1.981833: one
    unit in the last digit of a number printed to 6 or more significant digits passes, two do
    not, and a short number's last digit is compared as it is."""
    assert text_matches("  mode  1      1.981832 Hz", "  mode  1      1.981833 Hz")
    assert text_matches("4.630118e+03", "4.630117e+03")
    assert not text_matches("  mode  1      1.981831 Hz", "  mode  1      1.981833 Hz")
    assert not text_matches("t = 1.26 s", "t = 1.25 s")


def test_iteration_counts_follow_round_off():
    """Another BLAS kernel (OpenBLAS's Sandybridge) takes 65 Newton iterations where this
    machine takes 63: counts of iterations and load steps are not compared; the rest is."""
    assert text_matches(
        "static equilibrium: 11 load steps, 65 Newton iterations",
        "static equilibrium: 11 load steps, 63 Newton iterations",
    )
    assert not text_matches("11 load steps, 65 Newton iterations", "11 load steps, 65 iterations")


def test_a_real_change_fails():
    assert not text_matches("0.01,0.50000063346,0.500000393517,-0.000489849441738", HERE)
    assert not text_matches("  mode  1      1.938585 Hz", "  mode  1      1.938485 Hz")
    assert not text_matches("1000 steps, 2198 Newton iterations", "1000 steps, 2198 iterations")
    assert not text_matches("rancf 0.2.1", "rancf 0.2.0")  # versions are text
    assert not text_matches("run_00001.vtu", "run_00000.vtu")  # so are names
    assert not text_matches("completed: t = 1 s", "completed: t = 1 ms")
    assert not text_matches("0.5 0.5", "0.5")


def test_rows_compare_cell_by_cell():
    a = [{"run": "0000_k=0.3", "AB": "0.50000063346", "status": "completed"}]
    b = [{"run": "0000_k=0.3", "AB": "0.50000063347", "status": "completed"}]
    assert_rows_match(a, b)
    try:
        assert_rows_match(a, [{**b[0], "status": "failed"}])
    except AssertionError:
        pass
    else:  # pragma: no cover
        raise AssertionError("a different status must not match")
