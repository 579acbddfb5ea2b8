#!/usr/bin/env python3
"""doc_links.py SOURCE_DIR: every relative link in README.md and the pages
under docs/ points at a file that exists, and a link with #anchor at a
heading of that page.

A link is [text](target) or ![alt](target) outside code blocks and code
spans; targets with a scheme (https:, mailto:) are left alone. An anchor is
a heading's text as GitHub makes it: lower case, formatting and punctuation
other than - and _ dropped, spaces turned into -, and -1, -2, ... added to
a repeated one. Prints one line for each broken link, exits 1 if any.
"""
import os
import re
import sys

LINK = re.compile(r'!?\[((?:[^\[\]]|\[[^\]]*\])*)\]\(([^()\s]+)(?:\s+"[^"]*")?\)')
CODE_SPAN = re.compile(r'(`+)(.+?)\1')


def prose_lines(text):
    """(line number, line) outside fenced code blocks and HTML comments."""
    fence = None
    comment = False
    for number, line in enumerate(text.split('\n'), 1):
        stripped = line.lstrip()
        if fence:
            if stripped.startswith(fence):
                fence = None
            continue
        if comment:
            if '-->' in line:
                comment = False
            continue
        if stripped.startswith('```') or stripped.startswith('~~~'):
            fence = stripped[:3]
            continue
        if stripped.startswith('<!--') and '-->' not in stripped:
            comment = True
            continue
        yield number, line


def slug(heading):
    text = re.sub(r'!?\[((?:[^\[\]]|\[[^\]]*\])*)\]\([^)]*\)', r'\1', heading)
    text = text.replace('`', '').lower()
    text = ''.join(c for c in text if c.isalnum() or c in ' -_')
    return text.replace(' ', '-')


anchor_cache = {}


def anchors(path):
    if path not in anchor_cache:
        seen = {}
        found = set()
        with open(path, encoding='utf-8') as f:
            for _, line in prose_lines(f.read()):
                m = re.match(r'#{1,6}\s+(.*?)\s*#*\s*$', line)
                if not m:
                    continue
                base = slug(m.group(1))
                n = seen.get(base, 0)
                seen[base] = n + 1
                found.add(base if n == 0 else '%s-%d' % (base, n))
        anchor_cache[path] = found
    return anchor_cache[path]


def main():
    root = sys.argv[1]
    pages = [os.path.join(root, 'README.md')]
    for folder, _, files in os.walk(os.path.join(root, 'docs')):
        pages += [os.path.join(folder, f) for f in sorted(files) if f.endswith('.md')]
    broken = 0
    links = 0
    for page in pages:
        with open(page, encoding='utf-8') as f:
            text = f.read()
        name = os.path.relpath(page, root)
        for number, line in prose_lines(text):
            line = CODE_SPAN.sub(lambda m: ' ' * len(m.group(0)) if '](' not in m.group(2) else m.group(0), line)
            for m in LINK.finditer(line):
                target = m.group(2)
                if re.match(r'[A-Za-z][A-Za-z0-9+.-]*:', target):
                    continue
                links += 1
                path, _, anchor = target.partition('#')
                resolved = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
                if not os.path.exists(resolved):
                    print('%s:%d: %s: no such file' % (name, number, target))
                    broken += 1
                elif anchor and resolved.endswith('.md') and anchor not in anchors(resolved):
                    print('%s:%d: %s: no heading #%s in %s' %
                          (name, number, target, anchor, os.path.relpath(resolved, root)))
                    broken += 1
    print('%d links in %d pages checked, %d broken' % (links, len(pages), broken))
    return 1 if broken else 0


if __name__ == '__main__':
    sys.exit(main())
