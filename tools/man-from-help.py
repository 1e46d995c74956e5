#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""man-from-help: writes a program's man page from its --help text, so that the options are
written once, in the program, and the man page cannot drift from them.

  man-from-help.py --name NAME --summary TEXT --version TEXT [--subcommand SUB]...
                   [--see-also TEXT] --output FILE -- PROGRAM [ARG...]

Runs `PROGRAM ARG... --help` (and `PROGRAM ARG... SUB --help` for every --subcommand) with
COLUMNS=80 and turns the text into roff (man(7)):
  - the `usage:` line and its indented continuation lines: SYNOPSIS, PROGRAM's own name replaced
    by NAME;
  - an unindented line ending in ':' followed by indented lines: a subsection heading (`options:`);
  - an indented line `TERM  description` (two spaces or more between them), with continuation
    lines aligned on the description: a tagged paragraph (.TP); a term alone on its line may go
    on over lines indented deeper than it, its description on lines deeper still;
  - a paragraph starting `Exit status:` or `Exit codes:`: the EXIT STATUS section; the heading
    alone on its line followed by indented `STATUS  meaning` lines: each status a tagged paragraph
    of that section;
  - any other paragraph: a paragraph, its lines joined.
The rest of the top-level help is DESCRIPTION; each subcommand's help (after its usage) is a
section `NAME SUB`. Python 3 standard library only. Exits 1 when PROGRAM fails, 2 on usage errors.
"""

import argparse
import os
import re
import subprocess
import sys

ITEM = re.compile(r"^( +)(\S+(?: \S+)*?)(?: {2,}(\S.*))?$")
EXIT_STATUS = re.compile(r"^Exit (?:status|codes):\s*")


def roff_text(text):
    """Escapes text for roff: backslashes, minus signs (so that options copy as typed) and a
    leading control character."""
    text = text.replace("\\", "\\e").replace("-", "\\-")
    if text.startswith((".", "'")):
        text = "\\&" + text
    return text


def join_lines(lines):
    """Joins wrapped lines into one; a word wrapped after its hyphen (`sub-` / `index`) is joined
    without a space."""
    out = ""
    for line in (l.strip() for l in lines):
        if not out:
            out = line
        elif re.search(r"[A-Za-z]-$", out) and line[:1].isalpha():
            out += line
        else:
            out += " " + line
    return out


def run_help(command, subcommand=None):
    argv = command + ([subcommand] if subcommand else []) + ["--help"]
    env = dict(os.environ, COLUMNS="80")
    try:
        p = subprocess.run(argv, capture_output=True, text=True, env=env)
    except OSError as e:
        sys.exit("man-from-help.py: cannot run %s: %s" % (argv[0], e.strerror))
    if p.returncode != 0 or not p.stdout.strip():
        sys.exit("man-from-help.py: `%s` failed (exit status %d): %s"
                 % (" ".join(argv), p.returncode, p.stderr.strip() or "no output"))
    return [line.rstrip() for line in p.stdout.expandtabs().splitlines()]


def split_usage(lines, name):
    """Returns (synopsis lines without 'usage:' and with NAME, the remaining lines)."""
    for i, line in enumerate(lines):
        m = re.match(r"^usage:\s*(\S+)\s*(.*)$", line, re.IGNORECASE)
        if m:
            usage = [m.group(2)]
            j = i + 1
            while j < len(lines) and lines[j].startswith(" ") and lines[j].strip():
                usage.append(lines[j])
                j += 1
            return [name, join_lines(usage)], lines[:i] + lines[j:]
    sys.exit("man-from-help.py: no 'usage:' line in the help of %s" % name)


def paragraphs(lines):
    block = []
    for line in lines + [""]:
        if line.strip():
            block.append(line)
        elif block:
            yield block
            block = []


def render_items(lines):
    """Tagged paragraphs from indented `TERM  description` lines and their continuations."""
    items = []  # [indent, term, description lines, description column]
    for i, line in enumerate(lines):
        indent = len(line) - len(line.lstrip())
        m = ITEM.match(line)
        last = items[-1] if items else None
        following = lines[i + 1] if i + 1 < len(lines) else ""
        deeper_follows = len(following) - len(following.lstrip()) > indent
        if last and last[3] is not None and indent == last[3]:
            last[2].append(line)
        elif last and last[3] is None and indent > last[0] and not m.group(3) and deeper_follows:
            # A term too long for one line: its continuation, the description further right.
            last[1] += " " + line.strip()
        elif last and last[3] is None and indent > last[0] and not m.group(3):
            last[2].append(line)
            last[3] = indent
        else:
            column = None if not m.group(3) else line.index(m.group(3), indent + len(m.group(2)))
            items.append([indent, m.group(2), [m.group(3)] if m.group(3) else [], column])
    out = []
    for _, term, description, _ in items:
        out += [".TP", "\\fB%s\\fR" % roff_text(term)]
        if description:
            out.append(roff_text(join_lines(description)))
    return out


def render_body(lines):
    """Returns (body roff lines, exit status roff lines)."""
    body, exit_status = [], []
    for block in paragraphs(lines):
        is_list = not block[0].startswith(" ") and block[0].endswith(":") and len(block) > 1 \
            and all(l.startswith(" ") for l in block[1:])
        if is_list and EXIT_STATUS.fullmatch(block[0]):
            exit_status += render_items(block[1:])
        elif is_list:
            body += [".SS %s" % roff_text(block[0][:-1].capitalize())] + render_items(block[1:])
        elif all(l.startswith(" ") for l in block) and ITEM.match(block[0]).group(3):
            body += render_items(block)
        elif EXIT_STATUS.match(block[0]):
            exit_status += [".PP", roff_text(join_lines([EXIT_STATUS.sub("", block[0])] + block[1:]))]
        else:
            body += [".PP", roff_text(join_lines(block))]
    return body, exit_status


def synopsis(usage):
    return [".B %s" % roff_text(usage[0]), roff_text(usage[1]), ".br"]


def main():
    parser = argparse.ArgumentParser(prog="man-from-help.py",
                                     description="Write a man page from a program's --help text.")
    parser.add_argument("--name", required=True, help="the installed program's name")
    parser.add_argument("--summary", required=True, help="one line for the NAME section")
    parser.add_argument("--version", required=True, help="package and version for the footer")
    parser.add_argument("--subcommand", action="append", default=[], metavar="SUB",
                        help="also document `PROGRAM SUB --help` (repeatable)")
    parser.add_argument("--see-also", metavar="TEXT", help="the SEE ALSO section")
    parser.add_argument("--output", required=True, metavar="FILE")
    parser.add_argument("command", nargs="+", metavar="PROGRAM [ARG...]")
    args = parser.parse_args()

    usage, rest = split_usage(run_help(args.command), args.name)
    description, exit_status = render_body(rest)
    page = [".TH %s 1 \"\" \"%s\" \"User Commands\"" % (args.name.upper(), roff_text(args.version)),
            ".SH NAME", "%s \\- %s" % (roff_text(args.name), roff_text(args.summary)),
            ".SH SYNOPSIS"] + synopsis(usage)
    sections = []
    for sub in args.subcommand:
        sub_usage, sub_rest = split_usage(run_help(args.command, sub), args.name)
        page += synopsis(sub_usage)
        body, sub_exit = render_body(sub_rest)
        sections += [".SH \"%s %s\"" % (roff_text(args.name.upper()), roff_text(sub.upper()))]
        sections += body
        exit_status += sub_exit
    page += [".SH DESCRIPTION"] + description + sections
    if exit_status:
        page += [".SH \"EXIT STATUS\""] + exit_status
    if args.see_also:
        page += [".SH \"SEE ALSO\"", roff_text(args.see_also)]
    with open(args.output, "w") as f:
        f.write("\n".join(page) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
