"""The MeshSet fixture; shapes and checks the tests share live in the support package."""
import pymeshlab
import pytest

import pymeshlab_acd


@pytest.fixture
def ms():
    pymeshlab_acd.load()
    return pymeshlab.MeshSet()
