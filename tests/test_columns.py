"""The column definitions against the rows the pipeline makes, and the README's table against the definitions."""

from pathlib import Path

import pytest

from mdpipe.process import columns

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def keys():
    return columns.row_keys()


def test_every_key_of_a_row_is_defined_and_every_definition_is_a_key(keys):
    """A target's row and a `none` row: no undocumented column, no documented column that is not written."""
    undefined = []
    for key in keys:
        try:
            columns.definition(key)
        except KeyError:
            undefined.append(key)
    assert undefined == []
    assert [name for name in columns.BY_NAME if name not in keys] == []
    assert len(keys) == len(set(keys)) >= 36


def test_readme_table_is_the_generated_one(keys):
    """Drift: the README holds exactly the table rendered from the definitions (regenerate with
    `python -m mdpipe.process.columns --write-readme`)."""
    text = (ROOT / "README.md").read_text()
    assert columns.replace_block(text, columns.markdown_table(keys)) == text


def test_an_undefined_key_is_named():
    with pytest.raises(KeyError, match="column 'range_fuzz_m' has no definition in mdpipe/process/columns.py"):
        columns.definition("range_fuzz_m")


def test_status_columns_of_defined_features_get_the_generic_entry():
    entry = columns.definition("blade_length_m_status")
    assert entry.name == "blade_length_m_status" and "`blade_length_m`" in entry.meaning
    with pytest.raises(KeyError, match="'range_fuzz_m_status'"):
        columns.definition("range_fuzz_m_status")
    table = columns.markdown_table(["file", "blade_length_m", "blade_length_m_status"])
    rows, codes = table.split("\n\n")
    assert rows.count("\n| `") == 3 and "| `assumed_blades` |" in codes


def test_check_reports_drift(tmp_path, capsys):
    readme = tmp_path / "README.md"
    readme.write_text(f"intro\n{columns.START}\n| old table |\n{columns.END}\nrest\n")
    assert columns.main(["--check", "--readme", str(readme)]) == 1
    assert "differs from mdpipe/process/columns.py" in capsys.readouterr().err
    assert columns.main(["--write-readme", "--readme", str(readme)]) == 0
    assert columns.main(["--check", "--readme", str(readme)]) == 0
    text = readme.read_text()
    assert text.startswith("intro\n") and text.endswith(f"{columns.END}\nrest\n") and "| `notes` |" in text
