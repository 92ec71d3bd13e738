"""A small consolidated periodic RVE shared by the fem tests (prepared once per session)."""
import pytest

import talus


@pytest.fixture(scope="session")
def rve_file(tmp_path_factory):
    if not talus.build_info()["components"].get("fem", (False,))[0]:
        pytest.skip("this build has no fem component (see `talus info`)")
    from talus.fem import prepareRVE
    path = tmp_path_factory.mktemp("rve") / "rve.h5"
    info = prepareRVE(path, size=1.0, rMean=0.1, rRelFuzz=0.3, seed=1, sigma=-1e5, young=1e8)
    return path, info
