"""Labelled contact sheets for the figure scripts (scripts/*-figure*.sh, *-crops.sh): panels side by
side with a caption above each, rows stacked, written atomically.

    import sys; sys.path.insert(0, "scripts/figures")
    from contact_sheet import row, stack, save
    save(stack([row([a, b], ["plain", "reference"], box=(0, 0, 64, 64), scale=4)]), "docs/x.png")
"""
import os

from PIL import Image, ImageDraw


def _image(im):
    """A PIL image from a path, a PIL image or a float array of 8-bit levels (clipped)."""
    if isinstance(im, (str, os.PathLike)):
        return Image.open(im).convert("RGB")
    if isinstance(im, Image.Image):
        return im.convert("RGB")
    import numpy as np
    return Image.fromarray(np.clip(im, 0, 255).astype(np.uint8))


def row(images, labels, box=None, scale=1, gap=8, top=18, font=None, label_at=(4, 2)):
    """The images (cropped to box, enlarged scale times without smoothing) in a row, gap pixels apart,
    each under its label in a band of height top."""
    ims = [_image(im) for im in images]
    if box is not None:
        ims = [im.crop(box) for im in ims]
    w, h = ims[0].size
    sheet = Image.new("RGB", (len(ims) * (w * scale + gap) - gap, h * scale + top), "white")
    draw = ImageDraw.Draw(sheet)
    for k, (im, label) in enumerate(zip(ims, labels)):
        x = k * (w * scale + gap)
        sheet.paste(im.resize((w * scale, h * scale), Image.NEAREST) if scale != 1 else im, (x, top))
        draw.text((x + label_at[0], label_at[1]), label, fill="black", font=font)
    return sheet


def stack(rows, gap=10):
    """Rows one above the other, left-aligned, gap pixels apart."""
    sheet = Image.new("RGB", (max(r.width for r in rows), sum(r.height for r in rows) + gap * (len(rows) - 1)), "white")
    y = 0
    for r in rows:
        sheet.paste(r, (0, y))
        y += r.height + gap
    return sheet


def save(sheet, path, **options):
    """Write through a temporary name, so an interrupted script leaves no half-written figure."""
    tmp = f"{path}.tmp.png"
    sheet.save(tmp, **options)
    os.replace(tmp, path)
    return path
