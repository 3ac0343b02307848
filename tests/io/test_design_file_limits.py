"""Design files that once hung the reader or ended in a traceback: each now gives a clean DesignError, fast."""

import time

import pytest

from spiralbevel.errors import DesignError
from spiralbevel.io.design_file import MAX_PROBLEMS, default_design_text, load_design, parse_design


def _reason(err):
    return " ".join(str(p) for p in err.value.problems)


@pytest.mark.parametrize("encoding", ["latin-1", "utf-16", "utf-16-be", "cp1252"])
def test_non_utf8_files_are_refused_with_the_reason(tmp_path, encoding):
    f = tmp_path / "d.toml"
    f.write_bytes(default_design_text().replace("title = ", "title = \"Zahnräder\"\n_old_title = ").encode(encoding))
    with pytest.raises(DesignError) as err:
        load_design(f)
    assert "UTF" in _reason(err) and "design file" in _reason(err)


def test_binary_file_is_refused(tmp_path):
    f = tmp_path / "d.toml"
    f.write_bytes(bytes(range(256)) * 8)
    with pytest.raises(DesignError, match="UTF-8"):
        load_design(f)
    f.write_bytes(b"title = 'x'\n\x00\x00")
    with pytest.raises(DesignError, match="NUL"):
        load_design(f)


def test_utf8_with_bom_is_read(tmp_path):
    f = tmp_path / "d.toml"
    f.write_bytes(b"\xef\xbb\xbf" + default_design_text().encode())
    assert load_design(f).title == parse_design(default_design_text()).title


@pytest.mark.parametrize("text", ["x = " + "[" * 5000 + "]" * 5000, "x = " + "{a = " * 5000 + "1" + "}" * 5000,
                                  "x = " + "[" * 5000])
def test_deep_nesting_is_refused_before_the_recursive_parser(text):
    t0 = time.perf_counter()
    with pytest.raises(DesignError, match="nested"):
        parse_design(text)
    assert time.perf_counter() - t0 < 1.0


def test_brackets_inside_strings_and_comments_do_not_count():
    text = default_design_text() + "\n# " + "[" * 100 + "\n"
    text = text.replace("title = ", 'title = "' + "[" * 100 + '" #', 1)
    parse_design(text)


def test_file_size_is_bounded(tmp_path):
    f = tmp_path / "d.toml"
    f.write_bytes(b"# " + b"x" * (2 << 20))
    with pytest.raises(DesignError, match="too large"):
        load_design(f)


def test_many_unknown_keys_report_a_bounded_number_of_problems():
    # 200,000 unknown keys once printed 10.8 MB of error lines after 39 s; the file is now refused by its size, and a
    # file under the size limit lists at most MAX_PROBLEMS problems and counts the rest
    with pytest.raises(DesignError, match="too large"):
        parse_design("\n".join(f"k{i} = 1" for i in range(200_000)))
    t0 = time.perf_counter()
    with pytest.raises(DesignError) as err:
        parse_design(default_design_text() + "\n".join(f"\n[s{i}]\nk = 1" for i in range(5000)))
    problems = err.value.problems
    assert len(problems) == MAX_PROBLEMS + 1 and "more problem" in problems[-1].reason
    assert time.perf_counter() - t0 < 5.0


def test_long_values_and_keys_are_cut_in_messages():
    with pytest.raises(DesignError) as err:
        parse_design(default_design_text().replace("title = ", f'{"k" * 5000} = 1\ntitle = ', 1))
    assert len(str(err.value)) < 400


def test_directory_and_missing_file(tmp_path):
    with pytest.raises(DesignError, match="not a regular file"):
        load_design(tmp_path)
    with pytest.raises(DesignError, match="file not found"):
        load_design(tmp_path / "nope.toml")
