"""The validation page lists every record, marks failures and embeds the charts."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from talus import report, results  # noqa: E402


def test_page_has_cases_benchmarks_and_charts(tmp_path):
    folder = tmp_path / "results"
    case = results.Case("vans.poiseuille", quick=True, folder=folder)
    case.record("relative RMS error of the velocity profile", 2e-5, "analytic", 1e-4)
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    case.save_chart(fig, "profile")
    plt.close(fig)
    results.Case("dem.restitution", quick=True, folder=folder).record(
        "relative error | en", 0.5, "analytic", 1e-4)
    results.Case("dem.bench.quickperf", quick=False, folder=folder).record(
        "speed ratio", 6.2, "yade", 5.0, comparison=">=", peer="yade 2023.02a, 1 thread",
        ours=5084.0, theirs=820.0, unit="it/s", ratio=6.2)

    page = tmp_path / "docs" / "validation.md"
    text = report.render(folder, page)
    assert page.read_text() == text
    assert "2 of 3 records pass" in text
    assert "| vans.poiseuille | relative RMS error of the velocity profile | 2e-05 |" in text
    assert "relative error \\| en" in text and "**NO**" in text
    assert "| dem.bench.quickperf | yade 2023.02a, 1 thread | 5084 | 820 | it/s | 6.2 | >= 5 | yes | full |" in text
    assert "![vans.poiseuille.profile](validation/vans.poiseuille.profile.png)" in text
    assert (tmp_path / "docs" / "validation" / "vans.poiseuille.profile.png").is_file()


def test_a_cases_chart_goes_with_its_suffixed_records(tmp_path):
    folder = tmp_path / "results"
    case = results.Case("fem.shear-band", quick=True, folder=folder)
    case.record("peak", 0.03, "coarse mesh", 0.05, suffix="peak")
    case.record("angle", 0.0, "Mohr-Coulomb", 1.0, suffix="inclination")
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    case.save_chart(fig)
    plt.close(fig)
    # another case whose name merely starts alike gets no chart of this one
    results.Case("fem.shear", quick=True, folder=folder).record("e", 0.0, "x", 1.0, suffix="other")
    text = report.render(folder, tmp_path / "docs" / "validation.md")
    assert text.count("![fem.shear-band](validation/fem.shear-band.png)") == 1
    assert "### fem.shear\n" not in text


def test_cli_report(talus_cmd, tmp_path):
    folder = tmp_path / "results"
    results.Case("demo.one", quick=True, folder=folder).record("e", 0.0, "x", 1.0)
    talus_cmd("report", "--results", folder, "--output", tmp_path / "v.md")
    assert "demo.one" in (tmp_path / "v.md").read_text()
    missing = talus_cmd("report", "--results", tmp_path / "none", check=False)
    assert missing.returncode == 2 and "does not exist" in missing.stderr


def test_the_page_keeps_its_records_and_a_new_run_replaces_its_own(tmp_path):
    page = tmp_path / "docs" / "validation.md"
    first = tmp_path / "first"
    case = results.Case("dem.one", quick=True, folder=first)
    case.record("e", 0.5, "x", 1.0)
    fig, ax = plt.subplots()
    case.save_chart(fig)
    plt.close(fig)
    results.Case("dem.two", quick=True, folder=first).record("e", 0.5, "x", 1.0, detail=7)
    report.render(first, page)
    # another machine ran dem.two only: dem.one keeps its row, details and chart
    second = tmp_path / "second"
    results.Case("dem.two", quick=True, folder=second).record("e", 2.0, "x", 1.0)
    text = report.render(second, page)
    assert "1 of 2 records pass" in text
    assert "| dem.one | e | 0.5 |" in text and "| dem.two | e | 2 |" in text
    assert "![dem.one](validation/dem.one.png)" in text
    kept = {r["name"]: r for r in results.read_records(tmp_path / "docs" / "validation" / "records")}
    assert kept["dem.two"]["value"] == 2.0 and "detail" not in kept["dem.two"]
