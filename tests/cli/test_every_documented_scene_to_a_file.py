"""Every yaml block of README.md and the site's pages (docs/) that is a whole scene, saved as a user saves it and run
through ``hoistsim run`` to a file that opens with rows, its figures legible (tests/every_scene.py); every other block
said to be a fragment, with the reason.  The drawing guide's every-part drivetrain compiles for minutes: slow."""

from __future__ import annotations

import pytest
from every_scene import FRAGMENTS, blocks, document_scenes, fragment, runs_to_a_legible_file

import hoistsim
from hoistsim.errors import ScenarioError


@pytest.mark.parametrize("name, path, text", document_scenes())
def test_the_block_runs_to_a_file_with_rows_and_legible_figures(name, path, text, tmp_path, monkeypatch):
    runs_to_a_legible_file(name, path, text, tmp_path, monkeypatch)


def test_every_block_of_the_documents_is_a_scene_or_a_fragment_said_so():
    """The quick part of the blocks' check: every yaml block loads as a scene (without running it) or is
    listed in FRAGMENTS; and each fragment listed is still there and still does not load."""
    found = blocks()
    assert any(path == "README.md" for path, _, _ in found)
    assert any(path == "docs/how-to/draw-a-drivetrain.md" for path, _, _ in found)
    listed = set()
    for path, line, text in found:
        said = fragment(path, text)
        if said is None:
            hoistsim.scenario_from_text(text, source=f"{path}:{line}")
            continue
        listed.add(said)
        with pytest.raises(ScenarioError):
            hoistsim.scenario_from_text(text, source=f"{path}:{line}")
    assert listed == set(FRAGMENTS), f"listed as fragments but found nowhere: {set(FRAGMENTS) - listed}"
