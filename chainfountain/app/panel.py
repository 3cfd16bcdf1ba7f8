"""The panel's widgets (pygame_gui): the level's title, the buttons, and a slider with a
text field for each field the view shows (the student view: the level's two to four;
the expert view: every field, with its paper symbol and whether it applies live).

The readout between the buttons and the sliders is drawn by
:mod:`chainfountain.app.draw`; this module only builds and fills the widgets.
"""

from __future__ import annotations

import html
from dataclasses import dataclass

import pygame
from pygame_gui.elements import (
    UIButton,
    UIHorizontalSlider,
    UILabel,
    UIScrollingContainer,
    UITextEntryLine,
)

from chainfountain.app.controls import STUDENT_LABELS, FieldSpec
from chainfountain.app.text import px

GUI_FONT = 14
"""pygame_gui's text size (pixels at text scale 1)."""
TOOLTIP_WIDTH = 420
"""Width (px) a field's tooltip wraps at: the longest dotted path fits on a line."""
SCROLLBAR = 22
"""pygame_gui's scroll bar width (px, not scaled) plus a gap."""
ROW_H = 54
"""Height of one slider row (px at text scale 1)."""
BUTTONS = (("levels", "Levels", "Open another level (L)"),
           ("save", "Save", "Save the setup as a level (Ctrl+S)"),
           ("shot", "Picture", "A picture of the scene (F12)"),
           ("rec", "Clip", "Record a clip of the scene (G)"))
TOGGLES = (("plots", "Graphs", "The graphs under the scene on / off (V)"),
           ("expert", "Expert", "Every field and the paper's symbols (E)"),
           ("full", "Full view", "Hide the panel: the scene fills the window (Tab)"),
           ("help", "?", "Keys and mouse (H)"))


PLAIN_UNITS = frozenset({"m", "m/s", "deg", "g", "kg", "N", "s"})
"""Units the student view writes after a slider's name (the expert view writes all)."""


def gui_theme(scale: float) -> dict:
    """pygame_gui's theme at text scale ``scale``: its font for every element used."""
    size = str(round(GUI_FONT * scale))
    font = {"font": {"name": "noto_sans", "size": size}}
    theme = {t: font for t in ("label", "button", "text_entry_line", "text_box",
                               "selection_list", "tool_tip", "window", "horizontal_slider")}
    big = str(round(GUI_FONT * 1.3 * scale))
    theme["#title"] = {"font": {"name": "noto_sans", "size": big, "bold": "1"}}
    return theme


def tooltip(spec: FieldSpec, expert: bool = True) -> str:
    """A field's tooltip: what it is, what is allowed and how a change acts; the expert
    view's starts with the field's path and gives the level file's units too."""
    how = "applies live" if spec.live else "restarts the scene"
    span = ""
    if spec.narrowed and spec.slider_lo == spec.slider_hi:
        span = (f" Fixed here: with its other settings as they are, this level accepts only "
                f"{spec.slider_lo:.4g}{spec.shown_unit} (where it was measured to run); "
                "another is refused, and the message says why.")
    elif spec.narrowed and spec.refused_beyond:
        lo, hi = spec.slider_lo, spec.slider_hi
        span = (f" The slider spans {lo:.4g}-{hi:.4g}{spec.shown_unit}, the values this level "
                "accepts; a value typed beyond is refused, and the message says why.")
    elif spec.narrowed:
        lo, hi = spec.slider_lo, spec.slider_hi
        span = (f" The slider spans {lo:.4g}-{hi:.4g}{spec.shown_unit}, where this machine "
                "keeps running; a value typed beyond runs as a real machine would.")
    if not expert:
        allowed = spec.allowed().split("; in the level file", 1)[0]
        return html.escape(f"{spec.doc}. Allowed: {allowed}. Changing it {how}.{span}")
    return html.escape(f"{spec.path}: {spec.doc}. Allowed: {spec.allowed()}. Changing it "
                       f"{how}.{span}")


FIXED_NOTE = "fixed here"
"""What a row's label says while its slider is greyed out (a one-value span; the tooltip
says why)."""


def row_label(spec: FieldSpec, expert: bool, fixed: bool = False) -> str:
    """What a slider row is called: plain words with the unit (student view), the paper's
    name with the unit and whether it is live (expert view); ``fixed``: with
    :data:`FIXED_NOTE` (in the expert view instead of live or not: it does not move)."""
    unit = f" ({spec.unit})" if spec.unit and spec.unit != "1" else ""
    if expert:
        how = FIXED_NOTE if fixed else "live" if spec.live else "restarts"
        return f"{spec.label}{unit}  [{how}]"
    if spec.unit not in PLAIN_UNITS:  # a damper's N*s/m says nothing to a class
        unit = ""
    note = f" - {FIXED_NOTE}" if fixed else ""
    return f"{STUDENT_LABELS.get(spec.path, spec.label)}{unit}{note}"


def fit_label(label: UILabel, text: str) -> None:
    """Set ``label``'s text, cut with "..." to its width (pygame_gui would cut it off)."""
    font = label.font
    room = label.rect.w - 6
    if font.size(text)[0] > room:
        while text and font.size(text + "...")[0] > room:
            text = text[:-1]
        text = text.rstrip() + "..."
    label.set_text(text)


@dataclass
class ControlRow:
    """The widgets of one field."""

    spec: FieldSpec
    label: UILabel
    slider: UIHorizontalSlider
    entry: UITextEntryLine
    fixed: bool = False
    """The slider is greyed out: its span is one value (the label says so)."""


def build_buttons(ui, rect: pygame.Rect, y: int) -> tuple[dict[str, UIButton], int]:
    """The two rows of buttons across ``rect`` from ``y``; returns them and the y below."""
    buttons: dict[str, UIButton] = {}
    h = px(30)
    for row in (BUTTONS, TOGGLES):
        bw = (rect.w - px(12)) // len(row)
        for i, (key, label, tip) in enumerate(row):
            r = pygame.Rect(rect.x + px(6) + i * bw, y, bw - px(4), h)
            buttons[key] = UIButton(r, label, ui, tool_tip_text=tip)
        y += h + px(4)
    return buttons, y


def build_rows(ui, box: UIScrollingContainer, width: int, specs: list[FieldSpec],
               expert: bool) -> list[ControlRow]:
    """A row (label, slider, text field) per spec in the scrolling ``box`` of ``width``."""
    rows: list[ControlRow] = []
    y = px(4)
    entry_w = px(84)
    if len(specs) * px(ROW_H) + px(10) > box.get_container().get_rect().h:
        width -= SCROLLBAR  # the rows scroll: leave room for the bar
    for spec in specs:
        label = UILabel(pygame.Rect(px(6), y, width - px(12), px(22)), "", ui, container=box,
                        object_id="#field_label")
        fit_label(label, row_label(spec, expert))
        label.set_tooltip(tooltip(spec, expert), wrap_width=TOOLTIP_WIDTH)
        sw = width - entry_w - px(20)
        slider = UIHorizontalSlider(pygame.Rect(px(6), y + px(23), sw, px(26)), 0,
                                    (0.0, float(max(1, spec.positions))), ui, container=box,
                                    click_increment=1.0)
        entry = UITextEntryLine(pygame.Rect(px(10) + sw, y + px(22), entry_w, px(28)), ui,
                                container=box)
        entry.set_allowed_characters(list("0123456789.-+eE"))
        entry.set_tooltip(tooltip(spec, expert), wrap_width=TOOLTIP_WIDTH)
        rows.append(ControlRow(spec, label, slider, entry))
        y += px(ROW_H)
    box.set_scrollable_area_dimensions((width - px(4), y + px(6)))
    return rows
