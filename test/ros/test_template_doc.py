"""docs/NODE.md's rostest template is test/ros/template.test and test/ros/template_test.py
verbatim: the files the test command runs (template.test) are the ones users copy."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
# A fenced block right after a line naming the file: "`test/ros/<name>`" then ```lang.
BLOCK = r"`test/ros/{name}`[^\n]*\n+```\w*\n(.*?)^```"


def block_of(document, name):
    found = re.search(BLOCK.format(name=re.escape(name)), document, re.M | re.S)
    assert found, "docs/NODE.md has no block after `test/ros/%s`" % name
    return found.group(1)


def test_the_template_in_node_md_is_the_files_verbatim():
    document = (ROOT / "docs" / "NODE.md").read_text()
    for name in ("template.test", "template_test.py"):
        assert block_of(document, name) == (ROOT / "test" / "ros" / name).read_text(), (
            "docs/NODE.md's copy of test/ros/%s differs from the file" % name)
