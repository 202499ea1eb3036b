"""Tables that sort and filter in the browser, from ``file://`` and without a server.

Each table is an ITables DataTable in offline mode: the DataTables bundle
is written once, into ``assets/itables.js``, a classic script that every
page with a table loads (a module script would be refused from
``file://``).  Without JavaScript the page shows the plain HTML table
that ITables writes next to each DataTable.

Cells are HTML the site has already escaped (:func:`markupsafe.escape`,
links built around escaped names), so the tables are made with
``allow_html``; no text from a plugin reaches a page unescaped.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

import itables
import itables.options
import pandas as pd
from itables.javascript import generate_init_offline_itables_html
from markupsafe import Markup, escape

ASSET = "assets/itables.js"
"""Where the DataTables bundle is written, relative to the site's root."""

_NUMERIC_SORT = itables.JavascriptFunction(
    "function (data, type) {"
    " if (type !== 'sort' && type !== 'type') { return data; }"
    " const value = parseFloat(String(data).replace(/<[^>]*>/g, ''));"
    " return isNaN(value) ? -Infinity : value; }"
)
"""Sort a column of shown numbers (``12.5 [10.1, 14.0]``) by the number they start with; empty cells first."""


def write_bundle(site: Path) -> Path:
    """Write the DataTables bundle as ``assets/itables.js`` under ``site`` and return its path."""
    init = generate_init_offline_itables_html(itables.options.dt_bundle)
    script = re.search(r"<script>(.*?)</script>", init, flags=re.DOTALL)
    if script is None:
        raise RuntimeError("itables' offline init holds no script; is this itables 2?")
    path = site / ASSET
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(script.group(1), encoding="utf-8")
    return path


def escaped(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with every cell and column name as escaped HTML; cells already :class:`~markupsafe.Markup` stay."""
    return pd.DataFrame(
        {str(escape(str(column))): [str(escape("" if value is None else value)) for value in table[column]]
         for column in table.columns},
        dtype=object,
    )


def datatable(table: pd.DataFrame, table_id: str, numeric: Sequence[str] = ()) -> Markup:
    """An interactive table of ``table``, whose cells are HTML, all rows on one page.

    Parameters
    ----------
    table : pandas.DataFrame
        Cells as escaped HTML (:func:`escaped`).
    table_id : str
        The table's HTML id, unique on its page.
    numeric : sequence of str
        Columns (escaped names) of shown numbers, sorted by value and
        aligned right.

    Long column names may break after an underscore.
    """
    targets = [i for i, column in enumerate(table.columns) if column in set(numeric)]
    table = table.set_axis([str(column).replace("_", "_<wbr>") for column in table.columns], axis=1)
    column_defs = [{"targets": targets, "render": _NUMERIC_SORT, "className": "dt-right"}] if targets else []
    return Markup(
        itables.to_html_datatable(
            table,
            table_id=table_id,
            connected=False,
            allow_html=True,
            paging=False,
            showIndex=False,
            classes="display compact",
            columnDefs=column_defs,
            display_logo_when_loading=False,
            text_in_header_can_be_selected=False,
            autoWidth=False,
            layout={"topStart": None, "topEnd": "search", "bottomStart": "info", "bottomEnd": None},
            style="width: auto; margin: 0; caption-side: bottom",
        )
    )


def link(text: object, href: str) -> Markup:
    """``<a href=...>text</a>`` with both escaped."""
    return Markup('<a href="{}">{}</a>').format(href, text)
