/* The book's chapters in JupyterLab as on the site (`make lab`; scripts/lab.py adds this extension,
 * static/remoteEntry.js loads this file).
 *
 * jupyterlab-myst 2.7 renders the chapters' MyST but knows nothing of the book:
 *  - it has no bibliography: every cite node gets `error: true` and its key as text (its
 *    addCiteChildrenPlugin, src/citations.tsx; `references.cite` is always {order: [], data: {}},
 *    src/myst.ts processNotebookMDAST), shown as a yellow "Citation Not Found" mark;
 *  - it numbers the targets of the markdown cells only (src/myst.ts renderNotebook: "we may want to
 *    process the code cells as well, but not now"), so `[](#fig-arc)`, a figure made by a code cell
 *    labelled `#| label: fig-arc`, reads "#fig-arc".
 * This plain script (a hand-written JupyterLab federated extension: no build step, no network) mends
 * both in the rendered page, as the site shows them:
 *  - a citation reads "Flash & Hogan, 1985" (in a parenthetical group, with its prefix and suffix) or
 *    "Flash & Hogan (1985)", from references.bib at the root JupyterLab serves, with the full
 *    reference as its tooltip; a key that is not in references.bib keeps jupyterlab-myst's mark;
 *  - a figure reference reads "Figure 1.3", numbered as the site numbers it: the notebook's code
 *    cells labelled `#| label: fig-...` in order, with the enumerator of its first cell's front matter
 *    (`numbering: enumerator: "1.%s"`); a figure of another chapter is looked up in the other notebooks
 *    of the folder. Following the reference shows the figure's cell (opening its chapter if need be).
 * The notebook itself is never changed: only the text shown. ES5, like the site's scripts.
 */
(function () {
  "use strict";

  var NAME = "skilllib-book";
  var BIB_PATH = "references.bib";
  var KINDS = { fig: "Figure", tbl: "Table" };

  // ------------------------------------------------------------------ references.bib --

  var ACCENTS = { '"': "\u0308", "'": "\u0301", "`": "\u0300", "^": "\u0302", "~": "\u0303", "=": "\u0304", ".": "\u0307", c: "\u0327", v: "\u030c", u: "\u0306", H: "\u030b" };

  /** LaTeX of a bib field as plain text: accents composed, braces and escapes dropped. */
  function latexText(s) {
    s = s.replace(/\\([\"'`^~=.]|[cvuH](?=[\s{]))\s*\{?\s*(\\i|[A-Za-z])\s*\}?/g, function (all, acc, letter) {
      return (letter === "\\i" ? "i" : letter) + ACCENTS[acc];
    });
    s = s.replace(/\\([&%$#_])/g, "$1").replace(/---/g, "\u2014").replace(/--/g, "\u2013");
    s = s.replace(/[{}]/g, "").replace(/~/g, "\u00a0").replace(/\s+/g, " ").trim();
    return s.normalize ? s.normalize("NFC") : s;
  }

  /** The value starting at text[i] ({...}, "..." or a bare word): [value, index after it]. */
  function readValue(text, i) {
    var c = text.charAt(i);
    if (c === "{" || c === '"') {
      var depth = 0, j = i;
      for (; j < text.length; j++) {
        var d = text.charAt(j);
        if (d === "{") depth++;
        else if (d === "}") depth--;
        if ((c === "{" && depth === 0) || (c === '"' && d === '"' && j > i && depth === 0)) break;
      }
      return [text.slice(i + 1, j), j + 1];
    }
    var m = /^[^,}\s#]+/.exec(text.slice(i));
    return [m ? m[0] : "", i + (m ? m[0].length : 0)];
  }

  /** {key: {field: raw value}} of a .bib file's entries. */
  function parseBib(text) {
    var entries = {};
    var head = /@(\w+)\s*[{(]\s*([^,\s]+)\s*,/g;
    var m;
    while ((m = head.exec(text))) {
      if (/^(comment|string|preamble)$/i.test(m[1])) continue;
      var fields = { ENTRYTYPE: m[1].toLowerCase() };
      var i = head.lastIndex;
      for (;;) {
        var f = /^[\s,]*([A-Za-z][\w-]*)\s*=\s*/.exec(text.slice(i));
        if (!f) break;
        i += f[0].length;
        var parts = [];
        for (;;) {  // value # value # ...
          var v = readValue(text, i);
          parts.push(v[0]);
          i = v[1];
          var cat = /^\s*#\s*/.exec(text.slice(i));
          if (!cat) break;
          i += cat[0].length;
        }
        fields[f[1].toLowerCase()] = parts.join("");
      }
      entries[m[2]] = fields;
      head.lastIndex = i;
    }
    return entries;
  }

  /** The names of an author field: split on "and" outside braces. */
  function splitNames(field) {
    var names = [], depth = 0, start = 0;
    for (var i = 0; i < field.length; i++) {
      var c = field.charAt(i);
      if (c === "{") depth++;
      else if (c === "}") depth--;
      else if (depth === 0 && /\s/.test(c) && /^\s+and\s/.test(field.slice(i))) {
        names.push(field.slice(start, i));
        i += /^\s+and\s+/.exec(field.slice(i))[0].length - 1;
        start = i + 1;
      }
    }
    names.push(field.slice(start));
    return names.map(function (n) { return n.trim(); }).filter(Boolean);
  }

  /** A name's family part: a braced name ({scikit-learn developers}) is taken whole. */
  function family(name) {
    if (/^\{.*\}$/.test(name)) return latexText(name);
    var depth = 0;
    for (var i = 0; i < name.length; i++) {
      var c = name.charAt(i);
      if (c === "{") depth++;
      else if (c === "}") depth--;
      else if (c === "," && depth === 0) return latexText(name.slice(0, i));
    }
    var words = latexText(name).split(" ");
    return words[words.length - 1];
  }

  /** [author part, year] of an entry, as the site's citations show them. */
  function authorYear(entry) {
    var names = splitNames(entry.author || entry.editor || "").map(family);
    var who = names.length === 0 ? latexText(entry.title || "") :
      names.length === 1 ? names[0] :
      names.length === 2 ? names[0] + " & " + names[1] :
      names[0] + " et al.";
    var year = latexText(entry.year || (entry.date || "").slice(0, 4) || "n.d.");
    return [who, year];
  }

  /** The full reference, for a tooltip: "Authors (year). Title. Venue." */
  function fullReference(entry) {
    var names = splitNames(entry.author || entry.editor || "").map(latexText);
    var venue = entry.journal || entry.booktitle || entry.publisher || entry.howpublished || "";
    return [names.join("; ") + " (" + latexText(entry.year || "n.d.") + ")", latexText(entry.title || ""), latexText(venue)]
      .filter(Boolean).join(". ") + ".";
  }

  // ------------------------------------------------------------------ the page --

  /** The notebook panel and cell widget whose node holds el (or nulls). */
  function cellOf(app, el) {
    var panels = app.shell.widgets ? Array.from(app.shell.widgets("main")) : [];
    for (var p = 0; p < panels.length; p++) {
      var nb = panels[p].content;
      if (!nb || !nb.widgets || !panels[p].node.contains(el)) continue;
      for (var c = 0; c < nb.widgets.length; c++) {
        if (nb.widgets[c].node.contains(el)) return { panel: panels[p], cell: nb.widgets[c] };
      }
      return { panel: panels[p], cell: null };
    }
    return { panel: null, cell: null };
  }

  /** The cite nodes of a cell's MyST tree, in document order. */
  function citeNodes(cell) {
    var out = [];
    (function walk(node) {
      if (!node) return;
      if (node.type === "cite") out.push(node);
      (node.children || []).forEach(walk);
    })(cell && cell.mystModel && cell.mystModel.mdast);
    return out;
  }

  /** Replace a text node's content with text and "et al." in italics, as the site sets it. */
  function setCiteText(span, before, who, after) {
    var text = null;
    for (var n = span.firstChild; n; n = n.nextSibling) {
      if (n.nodeType === 3) { text = n; break; }
    }
    if (!text) return;
    var parts = (before + who + after).split("et al.");
    text.nodeValue = parts[0];
    var at = text.nextSibling;
    for (var i = 1; i < parts.length; i++) {
      var em = document.createElement("em");
      em.textContent = "et al.";
      span.insertBefore(em, at);
      span.insertBefore(document.createTextNode(parts[i]), at);
    }
  }

  function mendCitations(app, bib) {
    var marks = document.querySelectorAll('span[title="Citation Not Found"]:not([data-book-cite])');
    for (var i = 0; i < marks.length; i++) {
      var span = marks[i];
      var key = span.textContent.trim();
      var entry = bib[key];
      if (!entry) continue;  // not in references.bib: jupyterlab-myst's mark stays, as it should
      var node = null;
      var where = cellOf(app, span);
      if (where.cell) {  // its cite node: prefix, suffix and kind ([see @a, p. 3], @a)
        var nodes = citeNodes(where.cell);
        var spans = where.cell.node.querySelectorAll('[data-book-cite], span[title="Citation Not Found"]');
        var idx = Array.prototype.indexOf.call(spans, span);
        if (nodes.length === spans.length && nodes[idx] && nodes[idx].label === key) node = nodes[idx];
      }
      var narrative = node ? node.kind === "narrative" : !span.closest(".cite-group");
      var ay = authorYear(entry);
      var prefix = node && node.prefix ? node.prefix + " " : "";
      var suffix = node && node.suffix ? (/^[,;]/.test(node.suffix) ? "" : ", ") + node.suffix.trim() : "";
      span.setAttribute("data-book-cite", key);
      span.classList.remove("text-yellow-600");
      span.classList.add("book-cite");
      span.setAttribute("title", fullReference(entry));
      if (narrative) setCiteText(span, prefix, ay[0], " (" + ay[1] + suffix + ")");
      else setCiteText(span, prefix, ay[0], ", " + ay[1] + suffix);
    }
  }

  /** {label: {text: "Figure 1.3", index: cell index}} of a notebook's cells ([{type, source}], in order):
   * the code cells labelled `#| label: fig-...` numbered in order, with the enumerator of the first
   * markdown cell's front matter ("1.%s"), as the site numbers them. */
  function figureNumbers(cells) {
    var template = "%s", seenMarkdown = false;
    var numbers = {}, counts = {};
    for (var i = 0; i < cells.length; i++) {
      var src = cells[i].source;
      if (cells[i].type === "markdown" && !seenMarkdown) {
        seenMarkdown = true;
        var fm = /^---[ \t]*\n([\s\S]*?)\n---/.exec(src);
        var en = fm && /^\s*enumerator:\s*["']?([^"'\n]*%s[^"'\n]*)["']?\s*$/m.exec(fm[1]);
        if (en) template = en[1];
      }
      if (cells[i].type !== "code") continue;
      var head = /^(#\|.*(\n|$))+/.exec(src);  // the cell's leading `#|` options
      var m = head && /^#\|\s*label:\s*["']?(([a-z]+)-[\w-]+)/m.exec(head[0]);
      if (!m || !KINDS[m[2]]) continue;
      counts[m[2]] = (counts[m[2]] || 0) + 1;
      numbers[m[1]] = { text: KINDS[m[2]] + "\u00a0" + template.replace("%s", counts[m[2]]), index: i };
    }
    return numbers;
  }

  /** The cells of an open notebook panel, as figureNumbers reads them. */
  function panelCells(panel) {
    return panel.content.widgets.map(function (w) {
      return { type: w.model.type, source: w.model.sharedModel ? w.model.sharedModel.getSource() : "" };
    });
  }

  /** The figures of the other notebooks of a folder (the other chapters): a promise of
   * {label: {text, index, path}}, read once per folder through JupyterLab's contents service. */
  var folders = {};
  function folderFigures(app, dir, except) {
    if (!folders[dir]) {
      var contents = app.serviceManager.contents;
      folders[dir] = contents.get(dir, { content: true }).then(function (listing) {
        var notebooks = listing.content.filter(function (f) { return f.type === "notebook"; });
        return Promise.all(notebooks.map(function (f) {
          return contents.get(f.path, { content: true, type: "notebook" }).then(function (model) {
            var cells = model.content.cells.map(function (c) {
              return { type: c.cell_type, source: Array.isArray(c.source) ? c.source.join("") : c.source };
            });
            var numbers = figureNumbers(cells);
            for (var label in numbers) numbers[label].path = f.path;
            return numbers;
          }, function () { return {}; });
        }));
      }).then(function (all) {
        var merged = {};
        all.forEach(function (numbers) {
          for (var label in numbers) if (!merged[label]) merged[label] = numbers[label];
        });
        return merged;
      }, function () { return {}; });
    }
    return folders[dir].then(function (merged) {
      var out = {};
      for (var label in merged) if (merged[label].path !== except) out[label] = merged[label];
      return out;
    });
  }

  var elsewhere = {};  // panel path -> {label: target} of the other notebooks of its folder, once read

  function mendFigureReferences(app, queue) {
    var links = document.querySelectorAll('.jp-Notebook a[href^="#"]:not([data-book-ref])');
    var cache = [];
    for (var i = 0; i < links.length; i++) {
      var a = links[i];
      var label = a.getAttribute("href").slice(1);
      if (a.textContent.trim() !== "#" + label || !KINDS[label.split("-")[0]]) continue;
      var where = cellOf(app, a);
      if (!where.panel) continue;
      var known = null;
      for (var c = 0; c < cache.length; c++) if (cache[c][0] === where.panel) known = cache[c][1];
      if (!known) { known = figureNumbers(panelCells(where.panel)); cache.push([where.panel, known]); }
      var target = known[label];
      var path = where.panel.context ? where.panel.context.path : "";
      if (!target && path) {  // a figure of another chapter ([](#fig-padding) in chapter 1 is Figure 2.1)
        if (!elsewhere[path]) {
          elsewhere[path] = {};
          folderFigures(app, path.split("/").slice(0, -1).join("/"), path).then(function (found) {
            elsewhere[this] = found;
            queue();
          }.bind(path));
        }
        target = elsewhere[path][label];
      }
      if (!target) continue;
      var text = a.firstChild && a.firstChild.nodeType === 3 ? a.firstChild : null;
      if (!text) continue;
      text.nodeValue = target.text;
      a.setAttribute("data-book-ref", label);
      if (target.path) a.setAttribute("data-book-path", target.path);
      a.classList.add("book-ref");
    }
  }

  /** Scroll a notebook panel to its cell of the given figure label. */
  function reveal(panel, label) {
    var target = figureNumbers(panelCells(panel))[label];
    if (!target) return;
    var nb = panel.content;
    var cell = nb.widgets[target.index];
    nb.activeCellIndex = target.index;
    var reduce = window.matchMedia && window.matchMedia("(prefers-reduced-motion: reduce)").matches;
    cell.node.scrollIntoView({ block: "start", behavior: reduce ? "auto" : "smooth" });
  }

  /** Following a figure reference shows its cell (the figure is that cell's output), in the
   * chapter that has it. */
  function follow(app, event) {
    var a = event.target && event.target.closest ? event.target.closest("a[data-book-ref]") : null;
    if (!a) return;
    var label = a.getAttribute("data-book-ref");
    var path = a.getAttribute("data-book-path");
    var where = cellOf(app, a);
    event.preventDefault();
    event.stopPropagation();
    if (!path) {
      if (where.panel) reveal(where.panel, label);
      return;
    }
    app.commands.execute("docmanager:open", { path: path }).then(function (panel) {
      return panel.context.ready.then(function () { return panel.revealed; }).then(function () {
        reveal(panel, label);
      });
    });
  }

  var CSS = [
    ".jp-Notebook .book-cite { color: inherit; }",
    ".jp-Notebook .book-cite > svg { display: none; }",
    ".jp-Notebook a.book-ref { white-space: nowrap; }"
  ].join("\n");

  function activate(app) {
    var style = document.createElement("style");
    style.setAttribute("data-book", NAME);
    style.textContent = CSS;
    document.head.appendChild(style);

    var bib = null;
    var queued = false;
    function mend() {
      queued = false;
      if (bib) mendCitations(app, bib);
      mendFigureReferences(app, queue);
    }
    function queue() {
      if (!queued) { queued = true; window.requestAnimationFrame(mend); }
    }
    new MutationObserver(queue).observe(document.body, { childList: true, subtree: true, characterData: true });
    document.addEventListener("click", function (e) { follow(app, e); }, true);
    app.serviceManager.contents.get(BIB_PATH, { content: true, type: "file", format: "text" }).then(
      function (model) { bib = parseBib(model.content); queue(); },
      function () { bib = null; }  // no references.bib where JupyterLab serves: the marks stay
    );
    queue();
  }

  var plugin = {
    id: NAME + ":marks",
    description: "Citations and figure references of the book's chapters as the site shows them.",
    autoStart: true,
    activate: activate
  };

  // for remoteEntry.js, which hands the plugin to JupyterLab; the parsing, for tests (node or a page)
  window.SKILLLIB_BOOK_LAB = {
    plugin: plugin,
    bib: { parse: parseBib, authorYear: authorYear, fullReference: fullReference }
  };
})();
