#!/usr/bin/env python3
"""Subsets egui's four default fonts to the characters the page can show (docs/web.md, "A lighter
page"). The page's wasm carried them whole: 1.41 MB of TrueType, which brotli barely shrinks.
The subsets are committed here and compiled into the web build alone (src/app/page_fonts.rs); the
native window keeps egui's fonts whole.

What is kept, in every font (each keeps those of the characters it has):
- the text of any language written in Latin script, Greek and the signs of physics: Basic
  Latin, Latin-1, Latin Extended-A and B, IPA extensions, spacing modifiers and combining
  diacritics, Greek, general punctuation, super- and subscripts, currency, letterlike symbols,
  number forms, arrows, mathematical operators, miscellaneous technical, geometric shapes,
  miscellaneous symbols and dingbats (the blocks the panels draw their symbols from);
- every other character written in rigidlab's source, its levels and assignments, and egui's,
  epaint's and bevy_egui's sources (their widgets' symbols), except the CJK and Hangul of
  egui's tests and comments.
Left out: Cyrillic (Ubuntu and Hack have it), the emoji the page never writes, and the
rest of the emoji fonts. A level file or a link that writes a character left out shows it as
egui's missing-glyph box in the page (the native window shows it).

Hinting and layout tables are kept (egui hints with skrifa), so the glyphs drawn are the same.
Each subset is renamed "<name> derivative rigidlab" as the Ubuntu Font Licence asks of a
modified version (UFL.txt, 2c); the licences of the four fonts are kept beside them.

Usage: python3 web/fonts/subset.py  (fontTools, `pip install fonttools`; reads the fonts from
the epaint_default_fonts crate in Cargo's registry, at the version in Cargo.lock)
"""

import glob
import os
import re
import sys

from fontTools import subset

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

RANGES = [
    (0x20, 0x7E), (0xA0, 0x24F), (0x250, 0x2FF), (0x300, 0x36F), (0x370, 0x3FF),
    (0x2000, 0x206F), (0x2070, 0x209F), (0x20A0, 0x20CF), (0x2100, 0x214F), (0x2150, 0x218F),
    (0x2190, 0x21FF), (0x2200, 0x22FF), (0x2300, 0x23FF), (0x25A0, 0x25FF), (0x2600, 0x26FF),
    (0x2700, 0x27BF), (0x27F0, 0x27FF), (0x2B00, 0x2BFF), (0xFFFD, 0xFFFD),
]
FONTS = {
    "Hack-Regular.ttf": "Hack-Regular.ttf",
    "Ubuntu-Light.ttf": "Ubuntu-Light.ttf",
    "NotoEmoji-Regular.ttf": "NotoEmoji-Regular.ttf",
    "emoji-icon-font.ttf": "emoji-icon-font.ttf",
}
TEXT = (".rs", ".ron", ".md", ".toml")


def crate_dir(name):
    lock = open(os.path.join(ROOT, "Cargo.lock"), encoding="utf-8").read()
    version = re.search(r'name = "%s"\nversion = "([^"]+)"' % re.escape(name), lock).group(1)
    home = os.environ.get("CARGO_HOME", os.path.expanduser("~/.cargo"))
    found = glob.glob(os.path.join(home, "registry", "src", "*", f"{name}-{version}"))
    if not found:
        sys.exit(f"{name} {version} is not in Cargo's registry: build the page once first")
    return found[0]


def written(folders):
    """Every character above ASCII in the text files under `folders`."""
    out = set()
    for folder in folders:
        for dirpath, _, files in os.walk(folder):
            for f in files:
                if f.endswith(TEXT):
                    with open(os.path.join(dirpath, f), encoding="utf-8", errors="ignore") as fh:
                        out.update(ord(c) for c in fh.read() if ord(c) > 0x7E)
    # CJK, kana and Hangul (egui's tests and comments), which none of the fonts has anyway.
    return {c for c in out if not (0x2E80 <= c <= 0xD7FF or 0xF900 <= c <= 0xFAFF)}


def rename(font):
    """Appends "derivative rigidlab" to the family, full, unique and PostScript names."""
    for rec in font["name"].names:
        if rec.nameID in (1, 3, 4, 16):
            rec.string = rec.toUnicode() + " derivative rigidlab"
        elif rec.nameID == 6:
            rec.string = rec.toUnicode() + "-derivative-rigidlab"


def main():
    ours = [os.path.join(ROOT, d) for d in ("src", "levels", "assignments")]
    egui = [os.path.join(crate_dir(c), "src") for c in ("egui", "epaint", "bevy_egui")]
    chars = written(ours + egui)
    for lo, hi in RANGES:
        chars.update(range(lo, hi + 1))
    fonts = os.path.join(crate_dir("epaint_default_fonts"), "fonts")
    for src, dst in FONTS.items():
        opts = subset.Options()
        opts.layout_features = ["*"]
        opts.name_IDs = ["*"]
        opts.notdef_outline = True
        opts.glyph_names = False
        font = subset.load_font(os.path.join(fonts, src), opts)
        sub = subset.Subsetter(opts)
        sub.populate(unicodes=sorted(chars))
        sub.subset(font)
        rename(font)
        out = os.path.join(HERE, dst)
        subset.save_font(font, out, opts)
        print(f"{dst}: {os.path.getsize(os.path.join(fonts, src))} -> {os.path.getsize(out)} bytes")


if __name__ == "__main__":
    main()
