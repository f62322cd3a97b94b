#!/usr/bin/python3
"""The documentation's claims, checked against the program and the repository:
- the README's scene and the scene-format page's example are examples/drape.yaml (the main job),
  line for line without its comments (mlshell's --help example is checked by a unit test,
  SceneFormatHelp.ExampleIsTheMainJobsDrape);
- docs/scene-format.md documents exactly the keys, effects and selections `mlshell --help` lists;
- every relative link in README.md, examples/README.md and docs/*.md points at a file or folder that exists.

  /usr/bin/python3 tests/docs/check_docs.py build/mlshell ."""
import re
import subprocess
import sys
from pathlib import Path

failures = []


def fail(message):
    failures.append(message)


def yaml_blocks(text):
    return re.findall(r"```yaml\n(.*?)```", text, re.S)


def drape_lines(root):
    text = (root / "examples" / "drape.yaml").read_text()
    return [line for line in text.splitlines() if line and not line.startswith("#")]


def check_example_scenes(root):
    drape = drape_lines(root)
    for page in ["README.md", "docs/scene-format.md"]:
        blocks = yaml_blocks((root / page).read_text())
        if not blocks:
            fail(f"{page}: no ```yaml scene")
        elif blocks[0].splitlines() != drape:
            fail(f"{page}: its first scene is not examples/drape.yaml (without comments)")


# A key in --help: a word followed by ':' where a YAML key can stand (line start, after '{' or
# ', ' or '- '), outside the prose of the WHERE and EXAMPLE sections' explanations.
HELP_KEY = re.compile(r"(?:^\s*(?:- )?|[{,]\s*)([a-z_]+):", re.M)
HELP_EFFECT = re.compile(r"^\s+- ([a-z_]+)", re.M)
HELP_SELECTION = re.compile(r"\b((?:boundary|corner|point|group)\([^)]*\))")


def help_vocabulary(mlshell):
    out = subprocess.run([mlshell, "--help"], capture_output=True, text=True, check=True).stdout
    start = out.index("SCENE FILE FORMAT")
    end = out.index("\nEXAMPLE")
    fmt = out[start:end]
    keys = set(HELP_KEY.findall(fmt))
    effects = set(HELP_EFFECT.findall(fmt[: fmt.index("initial_state:")]))
    return keys | effects, fmt


def page_vocabulary(page_text):
    """Keys the page documents: the first column of its tables, each `name` in it."""
    keys = set()
    for line in page_text.splitlines():
        if not line.startswith("| `"):
            continue
        first = line.split("|")[1]
        keys.update(re.findall(r"`([a-z_]+)`", first))
    return keys


def check_scene_format(mlshell, root):
    page = (root / "docs" / "scene-format.md").read_text()
    in_help, fmt = help_vocabulary(mlshell)
    in_page = page_vocabulary(page)
    # Selection names are written as calls (boundary(left)); bare words in the page's first
    # column that are selections are not keys of --help.
    selections = {"boundary"}
    for key in sorted(in_help - in_page):
        fail(f"docs/scene-format.md: --help lists `{key}`, the page's tables do not")
    for key in sorted(in_page - in_help - selections):
        fail(f"docs/scene-format.md: the page documents `{key}`, --help does not list it")
    for sel in sorted(set(HELP_SELECTION.findall(fmt))):
        word = sel.split("(")[0]
        if word + "(" not in page:
            fail(f"docs/scene-format.md: --help's selection {sel} is not on the page")
    if not in_help or not in_page:
        fail("no keys found: the extraction is broken")
    return in_help, in_page


LINK = re.compile(r"\]\(([^)\s]+)\)")


def check_links(root):
    pages = [root / "README.md", root / "examples" / "README.md"] + sorted((root / "docs").glob("*.md"))
    for page in pages:
        for target in LINK.findall(page.read_text()):
            if re.match(r"[a-z]+:", target) or target.startswith("#"):
                continue
            path = target.split("#")[0]
            if not (page.parent / path).exists():
                fail(f"{page.relative_to(root)}: link to '{target}', which does not exist")


def main():
    mlshell, root = sys.argv[1], Path(sys.argv[2]).resolve()
    check_example_scenes(root)
    in_help, in_page = check_scene_format(mlshell, root)
    check_links(root)
    if failures:
        print("\n".join(failures))
        sys.exit(1)
    print(f"docs: {len(in_help)} keys in --help and on docs/scene-format.md; examples and links ok")


main()
