// Offline renderer of the book's MyST site.
//
// `myst build --html` runs this file (theme/template.yml, `build: render`) with
//   CONTENT_CDN      http://localhost:PORT serving config.json, content/<slug>.json and the public
//                    files (images, notebooks) of the already-transformed MyST project;
//   BUILD_DIRECTORY  where the static site goes (relative to the directory myst runs in).
// It writes one HTML file per page (index.html, <slug>.html) with relative links only, the images
// and notebooks the pages use, KaTeX's CSS and fonts, and a search index loaded as a <script>, so the
// site opens from the file system. Any page that fails to render, or a toc entry myst did not
// build, makes it exit 1 with a message naming the page.
//
// mystmd has already done the hard parts: numbering, cross-reference resolution, citations, and
// math (each math node carries KaTeX HTML). This file maps the MyST AST to HTML (hastscript) and
// adds the page shell: contents, search, the page's outline ("On this page"), copy buttons on code,
// hover previews of cross-references (each page carries the previews of the targets it refers to, as
// <template data-xref="page.html#id">), a light/dark switch, downloads and a footer with the book's
// version, commit and build date (BOOK_VERSION, BOOK_COMMIT, BOOK_BUILD_DATE from scripts/build_site.py).

import fs from 'node:fs';
import path from 'node:path';
import crypto from 'node:crypto';
import { fileURLToPath } from 'node:url';
import { h } from 'hastscript';
import { toHtml } from 'hast-util-to-html';
import { createLowlight, common } from 'lowlight';
import katex from 'katex';
import MiniSearch from 'minisearch';
import { micromark } from 'micromark';

const THEME = path.dirname(fileURLToPath(import.meta.url));
const require_ = (p) => path.join(THEME, 'node_modules', p);
const lowlight = createLowlight(common);
// The search index's fields: static/search.js builds a MiniSearch index with these options from the
// sections' text in _static/search-index.js, the first time the search box is used.
const SEARCH_OPTIONS = {
  fields: ['page', 'section', 'text'],
};

// ---------------------------------------------------------------- input and output -------------

const CDN = process.env.CONTENT_CDN;
if (!CDN) fail('CONTENT_CDN is not set: run this through `myst build --html` (site: template: ./theme).');
const OUT = resolveBuildDirectory(process.env.BUILD_DIRECTORY);

function fail(message) {
  process.stderr.write(`theme/render.mjs: ${message}\n`);
  process.exit(1);
}
function warn(message) {
  process.stderr.write(`theme warning: ${message}\n`);
}

// BUILD_DIRECTORY is relative to the directory myst runs in, but this command runs in theme/.
// That directory is $PWD when myst is started from a shell; otherwise look up the process chain
// (sh -c -> myst) for the one whose cwd holds myst's `_build/site/config.json` next to it.
function resolveBuildDirectory(dir) {
  if (!dir) fail('BUILD_DIRECTORY is not set: run this through `myst build --html`.');
  if (path.isAbsolute(dir)) return dir;
  const candidates = [process.env.PWD];
  try {
    let pid = process.ppid;
    for (let i = 0; i < 6 && pid > 1; i++) {
      candidates.push(fs.readlinkSync(`/proc/${pid}/cwd`));
      pid = Number(fs.readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1].split(' ')[1]);
    }
  } catch { /* not Linux, or the process is gone: PWD must do */ }
  for (const base of candidates.filter(Boolean)) {
    const out = path.resolve(base, dir);
    if (fs.existsSync(path.join(out, '..', 'site', 'config.json'))) return out;
  }
  fail(`cannot tell where BUILD_DIRECTORY=${dir} is (tried ${candidates.join(', ')}); run myst from the project folder.`);
}

// A connection the local server drops under load ("other side closed", reset) is tried again, up to
// FETCH_TRIES times with a growing pause; an HTTP error is final at once.
const FETCH_TRIES = 5;

async function fetchFrom(url, kind = 'json') {
  let res;
  for (let attempt = 1; ; attempt++) {
    try {
      res = await fetch(CDN + url);
      break;
    } catch (err) {
      if (attempt >= FETCH_TRIES) {
        throw new Error(`cannot reach the myst content server at ${CDN}${url} (${attempt} tries): ${err.cause?.message ?? err.message}`);
      }
      await new Promise((resolve) => setTimeout(resolve, 200 * attempt));
    }
  }
  if (!res.ok) throw new Error(`${url}: HTTP ${res.status} from the myst content server`);
  if (kind === 'json') return res.json();
  if (kind === 'text') return res.text();
  return Buffer.from(await res.arrayBuffer());
}

function write(rel, data) {
  const file = path.join(OUT, rel);
  fs.mkdirSync(path.dirname(file), { recursive: true });
  fs.writeFileSync(file, data);
}

// ---------------------------------------------------------------- small helpers ----------------

const text = (value) => ({ type: 'text', value: String(value ?? '') });
const raw = (value) => ({ type: 'raw', value: String(value ?? '') });
const hash = (s) => crypto.createHash('sha1').update(s).digest('hex').slice(0, 16);

// Jupyter text: drop ANSI colour codes and emulate carriage returns (progress bars).
function terminalText(s) {
  return String(s ?? '')
    .replace(/\x1b\[[0-9;?]*[A-Za-z]/g, '')
    .split('\n')
    .map((line) => line.split('\r').filter((part, i, all) => part !== '' || i === all.length - 1).pop() ?? '')
    .join('\n');
}

// The text of a MyST node, for alt text and the search index (blocks end with a space).
const BLOCKS = new Set(['paragraph', 'heading', 'listItem', 'tableCell', 'caption', 'captionNumber', 'admonitionTitle']);
function plainText(node) {
  if (!node) return '';
  if (typeof node.value === 'string' && ['text', 'inlineCode'].includes(node.type)) return node.value;
  const inner = (node.children ?? []).map(plainText).join('');
  return BLOCKS.has(node.type) ? `${inner} ` : inner;
}

function highlight(code, lang) {
  lang = (lang || '').toLowerCase();
  if (lang && lowlight.registered(lang)) {
    try {
      return lowlight.highlight(lang, code).children;
    } catch { /* fall through to plain text */ }
  }
  return [text(code)];
}

// A printed text that reads as prose (sentences) rather than a table: it may wrap on screen. Tabular
// prints (columns aligned by runs of spaces, rules of - = or box lines) keep their lines.
function isProse(t) {
  const lines = t.split('\n').filter((l) => l.trim());
  if (!lines.length) return false;
  const tabular = lines.filter((l) => /\S {2,}\S|^\s*[-=─━┄_]{4,}|[│┃|].*[│┃|]|\t/.test(l)).length;
  return tabular === 0 || (tabular === 1 && lines.length >= 4);
}

// A description of at most ~155 characters, cut at a word.
function clip(s, n = 155) {
  s = s.replace(/\s+/g, ' ').trim();
  if (s.length <= n) return s;
  return s.slice(0, s.lastIndexOf(' ', n - 1) > n / 2 ? s.lastIndexOf(' ', n - 1) : n - 1).replace(/[,;:.\s]+$/, '') + '…';
}

// Where pages link their source and the licence: BOOK_SOURCE_URL (e.g. https://github.com/org/repo/blob/main/),
// else BOOK_SOURCE_RELATIVE, the repository relative to the site (scripts/build_site.py; "../../" for
// _build/html). BOOK_SOURCE_ROOT is the checkout: only files that exist there are linked.
const SOURCE = {
  base: (() => { const b = process.env.BOOK_SOURCE_URL || process.env.BOOK_SOURCE_RELATIVE || '../../'; return b.endsWith('/') ? b : `${b}/`; })(),
  root: process.env.BOOK_SOURCE_ROOT || '',
};
function sourceExists(rel) { return !SOURCE.root || fs.existsSync(path.join(SOURCE.root, rel)); }
function sourceFile(file) {
  if (!file || !SOURCE.root) return null; // without the checkout we cannot tell which files are in it
  if (file.endsWith('.ipynb')) {
    const py = file.replace(/\.ipynb$/, '.py');
    if (sourceExists(py)) return py;
  }
  return sourceExists(file) ? file : null;
}

// ---------------------------------------------------------------- MyST AST -> hast -------------

// One Page renders one content/<slug>.json. `site` holds what every page shares.
class Page {
  constructor(site, entry, data) {
    this.site = site;
    this.entry = entry; // {slug, title, file}
    this.data = data;
    this.footnotes = new Map(); // identifier -> footnoteDefinition
    this.unknown = new Set();
    this.figureAlt = null; // caption text while inside a figure
    this.headings = []; // {depth, id, title (hast)} for the outline
    this.xrefTargets = new Set(); // "page.html#id" of every cross-reference on the page (for previews)
  }

  all(nodes) {
    return (nodes ?? []).flatMap((n) => this.one(n));
  }

  one(node) {
    const fn = this[`n_${node.type}`];
    if (fn) return fn.call(this, node) ?? [];
    if (!this.unknown.has(node.type)) {
      this.unknown.add(node.type);
      warn(`page ${this.entry.file}: no rule for MyST node "${node.type}"; rendering its children.`);
    }
    return this.all(node.children);
  }

  id(node) {
    return node.html_id || node.identifier || undefined;
  }

  // --- links ---------------------------------------------------------------------------------
  // mystmd gives internal URLs as site routes ("/", "/slug", "/slug#id") and files as "/name.ext".
  href(url) {
    if (!url) return url;
    if (!url.startsWith('/') || url.startsWith('//')) return url;
    const [route, frag] = url.split('#');
    const slug = route === '/' ? this.site.indexSlug : route.slice(1);
    const file = this.site.pageFiles.get(slug);
    if (file) return file + (frag ? `#${frag}` : '');
    return this.site.asset(route) + (frag ? `#${frag}` : '');
  }

  // --- blocks --------------------------------------------------------------------------------
  n_root(n) { return this.all(n.children); }
  n_block(n) {
    if (n.visibility === 'remove') return [];
    const props = { className: ['block', n.kind === 'notebook-code' ? 'cell' : null].filter(Boolean) };
    if (n.label) props.id = this.id(n);
    if (n.data?.tags?.includes?.('scroll-output')) { // mystmd 1.11 keeps the tag but does not apply it
      for (const c of n.children ?? []) if (c.type === 'outputs') c.scroll = true;
    }
    const body = this.all(n.children);
    if (n.visibility === 'hide') return h('details', props, [h('summary', 'Show cell'), ...body]);
    return n.kind === 'notebook-code' ? h('div', props, body) : body;
  }
  n_paragraph(n) { return h('p', this.all(n.children)); }
  n_heading(n) {
    const id = this.id(n);
    const depth = Math.min(Math.max(n.depth ?? 2, 2), 6); // h1 is the page title
    const title = this.all(n.children);
    if (id && depth <= 3) this.headings.push({ depth, id, title: plainText(n).trim() });
    return h(`h${depth}`, { id }, [...title, id ? h('a.anchor', { href: `#${id}`, ariaLabel: 'Link to this section' }, '#') : null].filter(Boolean));
  }
  n_thematicBreak() { return h('hr'); }
  n_blockquote(n) { return h('blockquote', this.all(n.children)); }
  n_list(n) {
    return h(n.ordered ? 'ol' : 'ul', { start: n.ordered && n.start !== 1 ? n.start : undefined }, this.all(n.children));
  }
  n_listItem(n) {
    // Tight list items hold a single paragraph: unwrap it, as Markdown renderers do.
    const kids = !n.spread && n.children?.length === 1 && n.children[0].type === 'paragraph' ? n.children[0].children : n.children;
    return h('li', this.all(kids));
  }
  n_definitionList(n) { return h('dl', this.all(n.children)); }
  n_definitionTerm(n) { return h('dt', this.all(n.children)); }
  n_definitionDescription(n) { return h('dd', this.all(n.children)); }
  n_html(n) { return raw(n.value); }
  n_comment() { return []; }
  n_mystTarget() { return []; }
  n_mystDirective(n) { return this.all(n.children); }
  n_mystRole(n) { return this.all(n.children); }
  n_div(n) { return h('div', { className: n.class }, this.all(n.children)); }
  n_aside(n) { return h('aside.margin', this.all(n.children)); }
  n_details(n) { return h('details', this.all(n.children)); }
  n_summary(n) { return h('summary', this.all(n.children)); }
  n_card(n) { return h('div.card', this.all(n.children)); }
  n_cardTitle(n) { return h('p.card-title', this.all(n.children)); }
  n_grid(n) { return h('div.grid', this.all(n.children)); }
  n_tabSet(n) { return h('div.tabs', this.all(n.children)); }
  n_tabItem(n) { return h('section.tab', [h('p.tab-title', n.title ?? ''), ...this.all(n.children)]); }
  n_embed(n) { return this.all(n.children); }
  n_include(n) { return this.all(n.children); }

  n_admonition(n) {
    const kind = n.kind || 'note';
    const [first, ...rest] = n.children ?? [];
    const hasTitle = first?.type === 'admonitionTitle';
    const title = hasTitle ? this.all(first.children) : [text(kind[0].toUpperCase() + kind.slice(1))];
    const body = this.all(hasTitle ? rest : n.children);
    const cls = ['admonition', kind, ...(n.class ? String(n.class).split(/\s+/) : [])];
    if (cls.includes('dropdown')) return h('details', { className: cls }, [h('summary.admonition-title', title), ...body]);
    return h('aside', { className: cls }, [h('p.admonition-title', title), ...body]);
  }
  n_admonitionTitle(n) { return h('p.admonition-title', this.all(n.children)); }

  // --- code, math ----------------------------------------------------------------------------
  n_code(n) {
    if (n.visibility === 'remove') return [];
    const pre = h('pre', { className: ['code', n.executable ? 'code-input' : null].filter(Boolean) },
      h('code', { className: n.lang ? [`language-${n.lang}`] : undefined }, highlight(n.value ?? '', n.lang)));
    // Every code block has a copy button (static/site.js copies the <pre>'s text).
    const box = h('div.code-box', { id: n.executable ? undefined : this.id(n) }, [
      h('button.copy', { type: 'button', title: 'Copy the code', ariaLabel: 'Copy the code' }, 'Copy'), pre]);
    const withName = n.filename ? h('div.code-block', [h('div.code-filename', n.filename), box]) : box;
    return n.visibility === 'hide' ? h('details.code-hidden', [h('summary', 'Show code'), withName]) : withName;
  }
  n_inlineCode(n) { return h('code', n.value); }
  katexHtml(n, displayMode) {
    if (n.html) return n.html;
    // mystmd leaves `html` out when KaTeX failed; render the error visibly instead of dropping it.
    return katex.renderToString(n.value ?? '', { displayMode, throwOnError: false });
  }
  n_math(n) {
    const number = n.enumerator ? h('span.eq-number', `(${n.enumerator})`) : null;
    return h('div.math-block', { id: this.id(n) }, [h('div.math-body', [raw(this.katexHtml(n, true))]), number].filter(Boolean));
  }
  n_inlineMath(n) { return raw(this.katexHtml(n, false)); }

  // --- inline --------------------------------------------------------------------------------
  n_text(n) { return text(n.value); }
  n_emphasis(n) { return h('em', this.all(n.children)); }
  n_strong(n) { return h('strong', this.all(n.children)); }
  n_delete(n) { return h('del', this.all(n.children)); }
  n_underline(n) { return h('u', this.all(n.children)); }
  n_subscript(n) { return h('sub', this.all(n.children)); }
  n_superscript(n) { return h('sup', this.all(n.children)); }
  n_smallcaps(n) { return h('span.smallcaps', this.all(n.children)); }
  n_keyboard(n) { return h('kbd', this.all(n.children)); }
  n_abbreviation(n) { return h('abbr', { title: n.title }, this.all(n.children)); }
  n_break() { return h('br'); }
  n_span(n) { return h('span', { className: n.class }, this.all(n.children)); }
  n_si(n) { return h('span.si', n.children ? this.all(n.children) : [text(n.value ?? `${n.number ?? ''} ${n.unit ?? ''}`)]); }
  n_inlineExpression(n) { return this.all(n.children); }
  n_link(n) {
    // `[](#label)` with no target reaches us as an empty link: show it (myst has warned already).
    if (!n.children?.length && n.url?.startsWith('#')) return h('span.xref.unresolved', n.url);
    // `source:skilllib/x.py#L12` (the API pages, scripts/api_page.py): a file of the repository, linked
    // as "View source" is (SOURCE); a file the checkout does not have is shown, not linked.
    if (n.url?.startsWith('source:')) {
      const rel = n.url.slice('source:'.length);
      if (SOURCE.root && !sourceExists(rel.split('#')[0])) return h('span.source-missing', this.all(n.children));
      return h('a.api-source', { href: SOURCE.base + rel, title: n.title }, this.all(n.children));
    }
    const href = this.href(n.url);
    const external = /^[a-z]+:/i.test(href ?? '');
    return h('a', { href, title: n.title, className: external ? ['external'] : undefined }, this.all(n.children));
  }
  n_crossReference(n) {
    const kids = n.children?.length ? this.all(n.children) : [text(n.label ?? n.identifier)];
    if (n.resolved === false) return h('span.xref.unresolved', kids);
    const href = n.remote && n.url ? this.href(`${n.url}#${n.html_id ?? n.identifier}`) : `#${n.html_id ?? n.identifier}`;
    const target = href.startsWith('#') ? `${this.entry.href}${href}` : href;
    this.xrefTargets.add(target);
    return h('a.xref', { href, dataXref: target }, kids);
  }
  n_footnoteReference(n) {
    const num = n.enumerator ?? n.label;
    return h('sup.footnote-ref', { id: `fnref-${n.identifier}` }, h('a', { href: `#fn-${n.identifier}` }, `${num}`));
  }
  n_footnoteDefinition(n) { this.footnotes.set(n.identifier, n); return []; }
  n_citeGroup(n) {
    const cites = (n.children ?? []).map((c) => this.n_cite(c));
    const joined = cites.flatMap((c, i) => (i ? [text('; '), c] : [c]));
    return n.kind === 'parenthetical' ? h('span.cite-group', [text('('), ...joined, text(')')]) : h('span.cite-group', joined);
  }
  n_cite(n) {
    const label = n.label ?? n.identifier;
    const kids = n.children?.length ? this.all(n.children) : [text(label)];
    return h('a.cite', { href: `#cite-${label}` }, kids);
  }

  // --- figures, tables, images ---------------------------------------------------------------
  n_container(n) {
    const captions = (n.children ?? []).filter((c) => c.type === 'caption' || c.type === 'legend');
    // A notebook figure cell (`#| label:` / `#| caption:`) holds its code too: show the code
    // above the figure, not inside it.
    const codes = (n.children ?? []).filter((c) => c.type === 'code' && c.executable);
    const body = (n.children ?? []).filter((c) => !captions.includes(c) && !codes.includes(c));
    const saved = this.figureAlt;
    this.figureAlt = plainText(captions.find((c) => c.type === 'caption')).trim() || saved;
    const inner = this.all(body);
    this.figureAlt = saved;
    const cap = captions.length ? h('figcaption', this.all(captions)) : null;
    const kind = n.kind || 'figure';
    const cls = ['figure', `figure-${kind}`, ...(n.class ? String(n.class).split(/\s+/) : [])];
    // Tables read better with the caption above; figures with it below.
    const children = kind === 'table' ? [cap, ...inner] : [...inner, cap];
    return [...this.all(codes), h('figure', { id: this.id(n), className: cls }, children.filter(Boolean))];
  }
  n_caption(n) { return this.all(n.children); }
  n_legend(n) { return h('div.legend', this.all(n.children)); }
  n_captionNumber(n) { return [h('span.caption-number', this.all(n.children)), text(' ')]; }
  n_image(n) {
    const src = this.href(n.url);
    const style = n.width ? `width: ${n.width}` : undefined;
    const img = h('img', { src, alt: n.alt ?? this.figureAlt ?? '', title: n.title, style, loading: 'lazy', decoding: 'async',
      className: n.align ? [`align-${n.align}`] : undefined });
    return this.figureAlt != null ? h('span.image-frame', img) : img;
  }
  n_iframe(n) { return h('div.iframe-note', ['Embedded content: ', h('a', { href: n.src }, n.src)]); }
  n_table(n) {
    const rows = n.children ?? [];
    let headRows = 0;
    while (headRows < rows.length && rows[headRows].children?.every((c) => c.header)) headRows++;
    const tr = (r) => h('tr', this.all(r.children));
    return h('div.table-wrap', h('table', [
      headRows ? h('thead', rows.slice(0, headRows).map(tr)) : null,
      h('tbody', rows.slice(headRows).map(tr)),
    ].filter(Boolean)));
  }
  n_tableRow(n) { return h('tr', this.all(n.children)); }
  n_tableCell(n) {
    return h(n.header ? 'th' : 'td', { align: n.align, colSpan: n.colspan, rowSpan: n.rowspan }, this.all(n.children));
  }

  // --- notebook outputs ----------------------------------------------------------------------
  n_outputs(n) {
    if (n.visibility === 'remove') return [];
    // Consecutive stream outputs of one name (stdout, stderr) read as one block.
    const merged = [];
    for (const o of n.children ?? []) {
      const d = o.jupyter_data;
      const prev = merged[merged.length - 1]?.jupyter_data;
      if (d?.output_type === 'stream' && prev?.output_type === 'stream' && prev.name === d.name) {
        merged[merged.length - 1] = { ...o, jupyter_data: { ...prev, text: prev.text + d.text } };
      } else merged.push(o);
    }
    const body = merged.flatMap((o) => this.one(o));
    if (!body.length) return [];
    const box = h('div.outputs', { className: n.scroll ? ['scroll'] : undefined }, body);
    return n.visibility === 'hide' ? h('details', [h('summary', 'Show output'), box]) : box;
  }
  n_output(n) {
    const d = n.jupyter_data;
    if (!d) return this.all(n.children);
    if (d.output_type === 'stream') {
      const t = terminalText(d.text);
      return h('pre', { className: ['output', 'stream', d.name, isProse(t) ? 'prose' : null].filter(Boolean) }, t);
    }
    if (d.output_type === 'error') {
      const tb = Array.isArray(d.traceback) ? d.traceback.join('\n') : d.traceback;
      return h('pre.output.error', terminalText(tb || `${d.ename}: ${d.evalue}`));
    }
    return this.mimeBundle(d.data ?? {}, d.metadata ?? {});
  }
  mimeBundle(data, metadata) {
    const content = (m) => data[m]?.content;
    // Retina PNGs carry their display size in the output metadata; CSS scales them down further.
    // Each image sits in a frame: at its drawn size on desktop, scrolled sideways on a phone (theme.css).
    const img = (m, src) => {
      const size = displaySize(data[m]?.pixels, metadata[m]);
      return h('span.image-frame', h('img.output', { src, alt: this.figureAlt ?? 'Cell output',
        width: size?.[0], height: size?.[1], loading: 'lazy', decoding: 'async' }));
    };
    for (const m of ['image/png', 'image/jpeg', 'image/gif', 'image/webp']) {
      if (data[m]?.path) return img(m, this.site.asset(data[m].path));
      if (content(m)) { // small images may come inline as base64
        return img(m, this.site.fileAsset(`${hash(content(m))}.${m.split('/')[1]}`, Buffer.from(content(m), 'base64')));
      }
    }
    if (data['image/svg+xml']) {
      const m = data['image/svg+xml'];
      return img('image/svg+xml', m.path ? this.site.asset(m.path) : this.site.fileAsset(`${hash(m.content)}.svg`, m.content));
    }
    if (content('text/html') != null) return h('div.output.html', [raw(content('text/html'))]);
    if (content('text/markdown') != null) return h('div.output.markdown', [raw(micromark(content('text/markdown')))]);
    if (content('text/latex') != null) {
      const tex = content('text/latex').trim().replace(/^\$\$?|\$\$?$/g, '');
      return h('div.output.latex', [raw(katex.renderToString(tex, { displayMode: true, throwOnError: false }))]);
    }
    if (content('text/plain') != null) return h('pre.output.text', terminalText(content('text/plain')));
    const types = Object.keys(data);
    if (types.length) warn(`page ${this.entry.file}: an output has only ${types.join(', ')}; not shown.`);
    return [];
  }

  // --- the page ------------------------------------------------------------------------------
  footnoteSection() {
    if (!this.footnotes.size) return null;
    const items = [...this.footnotes.values()]
      .sort((a, b) => Number(a.enumerator ?? 0) - Number(b.enumerator ?? 0))
      .map((fn) => h('li', { id: `fn-${fn.identifier}`, value: Number(fn.enumerator) || undefined }, [
        ...this.all(fn.children),
        h('a.footnote-back', { href: `#fnref-${fn.identifier}`, ariaLabel: 'Back to the text' }, '↩'),
      ]));
    return h('section.footnotes', [h('h2', 'Notes'), h('ol', items)]);
  }
  referenceSection() {
    const cite = this.data.references?.cite;
    if (!cite?.order?.length) return null;
    // Alphabetical, as an author-year list reads; each entry links its DOI (mystmd's formatted html).
    const sortKey = (label) => (cite.data[label]?.html ?? label).replace(/<[^>]*>/g, '').toLowerCase();
    const labels = [...cite.order].sort((a, b) => sortKey(a).localeCompare(sortKey(b)));
    return h('section.references', [h('h2#references', 'References'),
      h('ul', labels.map((label) => h('li', { id: `cite-${label}` }, [raw(cite.data[label]?.html ?? label)])))]);
  }
  render() {
    const fm = this.data.frontmatter ?? {};
    const body = this.all(this.data.mdast?.children);
    const downloads = this.site.downloads(this.entry, fm);
    const references = this.referenceSection();
    if (references) this.headings.push({ depth: 2, id: 'references', title: 'References' });
    return h('article.page', [
      h('header.page-header', [
        h('h1', [this.entry.chapter ? h('span.chapter-number', `${this.entry.chapter}`) : null, fm.title ?? this.entry.title].filter(Boolean)),
        fm.subtitle ? h('p.subtitle', fm.subtitle) : null,
        downloads.length ? h('p.download', [h('span.download-label', 'Download'),
          ...downloads.map((d) => h('a', { href: d.href, download: d.name, title: d.title }, [
            h('span', { ariaHidden: 'true' }, '⤓ '), d.name]))]) : null,
        this.sourceLink(),
      ].filter(Boolean)),
      ...[body].flat(),
      this.footnoteSection(),
      references,
    ].filter(Boolean));
  }

  // "View source": the page's file in the repository (a chapter's paired .py script rather than its
  // notebook), at BOOK_SOURCE_URL, or relative to the site in a checkout (scripts/build_site.py).
  sourceLink() {
    const rel = sourceFile(this.entry.file);
    if (!rel) return null;
    return h('p.view-source', h('a.source-link', { href: SOURCE.base + rel, title: `The source of this page: ${rel}` },
      [h('span', { ariaHidden: 'true' }, '</> '), 'View source ', h('code', rel)]));
  }

  // The page's description for <meta name="description">: its front matter's, else its first paragraph.
  description() {
    const fm = this.data.frontmatter ?? {};
    if (fm.description) return clip(String(fm.description));
    let first = null;
    const walk = (n) => {
      if (first || !n) return;
      if (n.type === 'paragraph') { const t = plainText(n).replace(/\s+/g, ' ').trim(); if (t.length > 20) first = t; return; }
      if (['code', 'outputs', 'container', 'admonition', 'aside'].includes(n.type)) return;
      (n.children ?? []).forEach(walk);
    };
    walk(this.data.mdast);
    return first ? clip(first) : null;
  }

  // "On this page": the page's sections (h2, h3). Wide screens show it beside the text, narrow ones
  // as a collapsed <details> above it; static/site.js opens it on wide screens and marks the section in view.
  outline() {
    if (!this.headings.length) return null;
    const items = this.headings.map((x) => h('li', { className: [`outline-level-${x.depth}`] },
      h('a', { href: `#${x.id}` }, x.title)));
    return h('nav#outline.outline', { ariaLabel: 'On this page' },
      h('details', [h('summary', 'On this page'), h('ol', items)]));
  }
}

// The width and height of a PNG from its IHDR chunk, or null.
function pngSize(buf) {
  if (!buf || buf.length < 24 || buf.readUInt32BE(12) !== 0x49484452) return null;
  return [buf.readUInt32BE(16), buf.readUInt32BE(20)];
}

// The CSS size of an output image. A high-resolution PNG (the kernel's retina figures, or a PNG file shown
// with a width of about half its pixels) is shown at half its pixels: the size it was drawn for, neither
// enlarged nor shrunk (its labels keep their size in points). Another keeps the width its output asks
// for, or its pixel size.
function displaySize(pixels, meta) {
  const w = Number(meta?.width) || null;
  if (!pixels) return w ? [w, Number(meta?.height) || undefined] : null;
  const [pw, ph] = pixels;
  const width = w ? (pw >= 1.5 * w ? pw / 2 : w) : pw;
  return [Math.round(width), Math.round((width * ph) / pw)];
}

// mystmd stores outputs over 25,000 characters apart (a `path` on the content server) and keeps a
// truncated text: put the whole text back before rendering. Images stay files (see mimeBundle).
async function inlineStoredOutputs(node) {
  const jobs = [];
  const walk = (n) => {
    const d = n.type === 'output' ? n.jupyter_data : null;
    if (d?.path && (d.output_type === 'stream' || d.output_type === 'error')) {
      jobs.push(fetchFrom(d.path, 'text').then((t) => { d[d.output_type === 'stream' ? 'text' : 'traceback'] = t; }));
    }
    for (const [mime, entry] of Object.entries(d?.data ?? {})) {
      if (entry?.path && entry.content == null && !mime.startsWith('image/')) {
        jobs.push(fetchFrom(entry.path, 'text').then((t) => { entry.content = t; }));
      }
      // a PNG's pixel size (from its header), for the <img>'s width and height (displaySize)
      if (mime === 'image/png' && entry?.path) {
        jobs.push(fetchFrom(entry.path, 'binary').then((b) => { entry.pixels = pngSize(b); }));
      } else if (mime === 'image/png' && entry?.content) {
        entry.pixels = pngSize(Buffer.from(entry.content.slice(0, 64), 'base64'));
      }
    }
    (n.children ?? []).forEach(walk);
  };
  walk(node);
  await Promise.all(jobs);
}

// ---------------------------------------------------------------- search index ----------------

// One search document per section (text between headings of depth <= 3: an API entry's "Parameters"
// or "Returns" stay in the entry's section) so results can jump to the section. `kind` ranks the
// results in the browser: chapters first, then the other pages, API entries last.
const SEARCH_SECTION_DEPTH = 3;
function searchKind(entry) {
  const file = entry.file ?? '';
  if (/^api([-_.]|$)/.test(path.posix.basename(file)) || /^api([-_.]|$)/.test(entry.href ?? '')) return 'api';
  if (file.endsWith('.ipynb') || entry.chapter) return 'chapter';
  return 'docs';
}
function searchDocuments(entry, data) {
  const href = entry.href;
  const kind = searchKind(entry);
  const docs = [];
  let current = { section: '', anchor: '', parts: [] };
  const flush = () => {
    const t = current.parts.join('').replace(/\s+/g, ' ').trim();
    if (t || current.section) {
      docs.push({ url: current.anchor ? `${href}#${current.anchor}` : href, page: entry.title, kind,
        section: current.section, text: t });
    }
  };
  const walk = (node) => {
    if (!node) return;
    if (node.type === 'heading' && (node.depth ?? 1) <= SEARCH_SECTION_DEPTH) {
      flush();
      current = { section: plainText(node).trim(), anchor: node.html_id ?? node.identifier ?? '', parts: [] };
      return;
    }
    if (['code', 'outputs', 'math', 'inlineMath', 'comment', 'html'].includes(node.type)) return;
    if (node.type === 'text' || node.type === 'inlineCode') current.parts.push(node.value);
    (node.children ?? []).forEach(walk);
    if (['paragraph', 'listItem', 'tableCell', 'caption', 'heading', 'break', 'tableRow'].includes(node.type)) current.parts.push(' ');
  };
  walk(data.mdast);
  flush();
  return docs;
}
// What _static/search-index.js holds: the pages (url, title, kind) and per section [page number,
// heading, anchor, text]; no prebuilt index (the text is smaller, and snippets need it).
function searchIndexData(documents) {
  const pages = [];
  const number = new Map();
  const sections = documents.map((d) => {
    const url = d.url.split('#')[0];
    if (!number.has(url)) {
      number.set(url, pages.length);
      pages.push({ url, title: d.page, kind: d.kind });
    }
    return [number.get(url), d.section, d.url.includes('#') ? d.url.slice(d.url.indexOf('#') + 1) : '', d.text];
  });
  return { version: 2, options: SEARCH_OPTIONS, pages, sections };
}

// ---------------------------------------------------------------- hover previews --------------

// What a cross-reference to an element of a page shows on hover: a figure or table with its caption,
// an equation, or a section's heading with its first paragraph(s). Keyed "page.html#id".
const PREVIEW_BLOCKS = new Set(['p', 'ul', 'ol', 'div', 'pre', 'aside', 'figure', 'table', 'dl']);
function isElement(node, tag) { return node?.type === 'element' && (!tag || node.tagName === tag); }
function classes(node) { return [node?.properties?.className ?? []].flat(); }

// A copy of a page's element for a preview on another page: no ids (they would repeat), links within
// its page made to point at that page.
function previewCopy(node, pageHref) {
  const copy = structuredClone(node);
  const walk = (n) => {
    if (n.properties) {
      delete n.properties.id;
      if (typeof n.properties.href === 'string' && n.properties.href.startsWith('#')) n.properties.href = `${pageHref}${n.properties.href}`;
    }
    n.children = (n.children ?? []).filter((c) => !(isElement(c) && classes(c).includes('anchor')));
    n.children.forEach(walk);
  };
  walk(copy);
  return copy;
}

function collectPreviews(pageHref, tree, into) {
  const walk = (parent) => {
    const kids = parent.children ?? [];
    kids.forEach((node, i) => {
      if (!isElement(node)) return;
      const id = node.properties?.id;
      if (id) {
        const key = `${pageHref}#${id}`;
        if (/^h[2-6]$/.test(node.tagName)) {
          // the heading and what follows it up to ~600 characters of text or the next heading
          const parts = [previewCopy(node, pageHref)];
          let chars = 0;
          for (const next of kids.slice(i + 1)) {
            if (!isElement(next)) continue;
            if (/^h[1-6]$/.test(next.tagName) || chars > 400 || parts.length > 3) break;
            if (!PREVIEW_BLOCKS.has(next.tagName)) continue;
            parts.push(previewCopy(next, pageHref));
            chars += JSON.stringify(next).length > 4000 ? 600 : plainHast(next).length;
          }
          into.set(key, parts);
        } else if (node.tagName === 'figure') {
          // the image(s) and the caption, not the text the figure's cell printed
          const fig = previewCopy(node, pageHref);
          const drop = (n) => { n.children = (n.children ?? []).filter((c) => !(isElement(c, 'pre') && classes(c).includes('output'))); n.children.forEach(drop); };
          drop(fig);
          into.set(key, [fig]);
        } else if (classes(node).includes('math-block')) {
          into.set(key, [previewCopy(node, pageHref)]);
        } else if (!into.has(key)) {
          into.set(key, [previewCopy(node, pageHref)]);
        }
      }
      walk(node);
    });
  };
  walk(tree);
}

function plainHast(node) {
  if (node.type === 'text') return node.value;
  return (node.children ?? []).map(plainHast).join('');
}

// ---------------------------------------------------------------- the page shell --------------

function tocNav(site, current) {
  const items = site.nav.map((e) => {
    if (!e.slug) return h('li.toc-part', e.title); // a toc entry with a title but no file
    const here = e.slug === current.slug;
    return h('li', { className: [`toc-level-${e.level ?? 1}`, here ? 'current' : null].filter(Boolean) },
      h('a', { href: e.href, ariaCurrent: here ? 'page' : undefined }, [
        e.chapter ? h('span.chapter-number', e.chapter) : null, e.label].filter(Boolean)));
  });
  return h('nav.toc', { ariaLabel: 'Contents' }, h('ol', items));
}

const HEAD_SCRIPT = "try{var t=localStorage.getItem('book-theme');if(t==='dark'||t==='light')document.documentElement.dataset.theme=t}catch(e){}";

function pageShell(site, entry, article, outline, previewKeys, description) {
  const i = site.pages.indexOf(entry);
  const prev = site.pages[i - 1];
  const next = site.pages[i + 1];
  const title = entry.slug === site.indexSlug ? site.title : `${entry.title} — ${site.title}`;
  const previews = previewKeys.map((key) => site.previews.get(key));
  // KaTeX's stylesheet only where there is math (in the text or in a preview the page carries).
  const hasMath = /class="katex/.test(toHtml([article, ...previews.flat()].filter(Boolean)));
  const search = h('div.search', { role: 'search' }, [
    h('label.visually-hidden', { htmlFor: 'search-input' }, 'Search the book'),
    h('input#search-input', { type: 'search', placeholder: 'Search the book…', autocomplete: 'off', spellcheck: 'false' }),
    h('ol#search-results', { hidden: true, ariaLive: 'polite' }),
  ]);
  const tree = h(null, [
    { type: 'doctype' },
    h('html', { lang: 'en' }, [
      h('head', [
        h('meta', { charset: 'utf-8' }),
        h('meta', { name: 'viewport', content: 'width=device-width, initial-scale=1' }),
        h('meta', { name: 'color-scheme', content: 'light dark' }),
        h('title', title),
        description || site.description ? h('meta', { name: 'description', content: description || clip(site.description) }) : null,
        site.authors.length ? h('meta', { name: 'author', content: site.authors.join(', ') }) : null,
        h('link', { rel: 'icon', href: '_static/favicon.svg', type: 'image/svg+xml' }),
        hasMath ? h('link', { rel: 'stylesheet', href: '_static/katex/katex.min.css' }) : null,
        h('link', { rel: 'stylesheet', href: '_static/theme.css' }),
        // the reader's light/dark choice, before the first paint (no flash of the other theme)
        h('script', HEAD_SCRIPT),
      ].filter(Boolean)),
      h('body', [
        h('a.skip-link', { href: '#content' }, 'Skip to the text'),
        h('header.topbar', [
          h('button#nav-toggle', { type: 'button', ariaControls: 'sidebar', ariaExpanded: 'false' }, [
            h('span.burger', { ariaHidden: 'true' }), h('span.visually-hidden', 'Contents')]),
          h('a.topbar-title', { href: site.pageFiles.get(site.indexSlug) }, site.title),
          h('button#theme-toggle', { type: 'button', title: 'Switch between light and dark', ariaLabel: 'Switch between light and dark' }, [
            h('span.theme-icon', { ariaHidden: 'true' })]),
        ]),
        h('div.layout', [
          h('aside#sidebar.sidebar', [
            h('a.site-title', { href: site.pageFiles.get(site.indexSlug) }, site.title),
            search,
            tocNav(site, entry),
            site.pdf ? h('p.pdf-link', h('a', { href: site.pdf, title: 'The whole book as one PDF file' }, [
              h('span', { ariaHidden: 'true' }, '⤓ '), 'The book as PDF'])) : null,
          ].filter(Boolean)),
          outline,
          h('main#content', [
            article,
            h('nav.prev-next', { ariaLabel: 'Previous and next page' }, [
              prev ? h('a.prev', { href: prev.href, rel: 'prev' }, [h('span.dir', '← Previous'), h('span.t', prev.label)]) : h('span'),
              next ? h('a.next', { href: next.href, rel: 'next' }, [h('span.dir', 'Next →'), h('span.t', next.label)]) : h('span'),
            ]),
            h('footer.site-footer', [
              h('span.build-version', ['Version ', h('strong', site.build.version)]),
              h('span.build-commit', ['Commit ', h('code', site.build.commit)]),
              h('span.build-date', ['Built ', site.build.date]),
              site.authors.length ? h('span.book-authors', ['By ', site.authors.join(', ')]) : null,
              site.license ? h('span.book-license', ['Licence ', site.license.href
                ? h('a', { href: site.license.href, rel: 'license' }, site.license.name) : site.license.name]) : null,
              site.pdf ? h('span.book-pdf', h('a', { href: site.pdf }, 'PDF of the book')) : null,
            ].filter(Boolean)),
          ]),
        ].filter(Boolean)),
        // Previews of the cross-references on this page (static/site.js shows them on hover).
        previewKeys.length ? h('div#xref-previews', { hidden: true }, previewKeys.map((key, k) =>
          h('template', { dataXref: key }, previews[k]))) : null,
        // Plain scripts with relative src: fetch() of file:// is blocked, <script src> is not. The search
        // index (search-index.js, minisearch.js) is loaded by search.js when the box is first used.
        h('script', { src: '_static/site.js' }),
        h('script', { src: '_static/search.js' }),
      ]),
    ]),
  ]);
  return toHtml(tree, { allowDangerousHtml: true }) + '\n';
}

// ---------------------------------------------------------------- main ------------------------

// The book's licence for the footer: myst.yml's `project.license` (myst hands it over normalised, with
// an SPDX id and a URL), else the first line of LICENSE in the checkout. Links the LICENSE file of the
// repository when there is one (works offline), else the licence's URL.
function bookLicense(project) {
  const lic = project.license?.content ?? project.license?.code ?? (typeof project.license === 'string' ? { id: project.license } : null);
  let name = lic?.id ?? lic?.name ?? null;
  const licenseFile = ['LICENSE', 'LICENSE.md', 'LICENSE.txt'].find((f) => SOURCE.root && fs.existsSync(path.join(SOURCE.root, f)));
  if (!name && licenseFile) name = fs.readFileSync(path.join(SOURCE.root, licenseFile), 'utf8').split('\n').find((l) => l.trim())?.trim() ?? null;
  if (!name) return null;
  return { name, href: licenseFile ? SOURCE.base + licenseFile : lic?.url ?? null };
}

function tocFiles(toc) {
  return (toc ?? []).flatMap((e) => [...(e.file ? [e.file] : []), ...tocFiles(e.children)]);
}

async function main() {
  const t0 = performance.now();
  const config = await fetchFrom('/config.json');
  if ((config.projects ?? []).length !== 1) fail(`expected one project in config.json, found ${(config.projects ?? []).length}.`);
  const project = config.projects[0];
  fs.mkdirSync(OUT, { recursive: true });

  // Pages in toc order: the index first, then project.pages (entries without slug are part titles).
  const entries = [{ slug: project.index, level: 0 }, ...project.pages];
  const failures = [];
  const contents = new Map();
  for (const e of entries.filter((x) => x.slug)) {
    try {
      const data = await fetchFrom(`/content/${e.slug}.json`);
      await inlineStoredOutputs(data.mdast ?? {});
      contents.set(e.slug, data);
    } catch (err) {
      failures.push(`page "${e.slug}": myst served no content (${err.message})`);
    }
  }
  const pageFiles = new Map(entries.filter((e) => e.slug).map((e) => [e.slug, e.slug === project.index ? 'index.html' : `${e.slug}.html`]));
  const title = project.title ?? config.title ?? 'Book';
  const pages = [];
  const nav = entries.map((e) => {
    const data = contents.get(e.slug);
    const file = (data?.location ?? '').replace(/^\//, '');
    const pageTitle = e.title ?? data?.frontmatter?.title ?? e.slug;
    // The landing page usually repeats the book title; call it "Introduction" in the contents.
    const label = e.slug === project.index ? (data?.frontmatter?.short_title ?? (pageTitle === title ? 'Introduction' : pageTitle)) : (e.short_title ?? pageTitle);
    // A chapter whose numbering is "N.%s" (scripts/build_site.py sets it) shows N before its title.
    const chapter = /^(\d+)\.%s$/.exec(data?.frontmatter?.numbering?.enumerator?.enumerator ?? '')?.[1];
    const item = { ...e, title: pageTitle, label, chapter, file, href: pageFiles.get(e.slug) };
    if (e.slug) pages.push(item);
    return item;
  });

  // Every toc file must have become a page: myst can drop a page and still carry on.
  const built = new Set(pages.map((p) => p.file));
  for (const f of tocFiles(project.toc)) {
    if (!built.has(f.replace(/^\.\//, ''))) failures.push(`toc entry "${f}": myst built no page for it (see the myst messages above).`);
  }

  // Files the pages refer to (images, notebooks, downloads) are collected while rendering and
  // fetched from the content server afterwards, into assets/ (or next to the page for notebooks).
  const pendingAssets = new Map(); // route -> relative output path
  const site = {
    title, description: project.description, indexSlug: project.index, pageFiles, pages, nav,
    authors: (project.authors ?? []).map((a) => a.name ?? a.nameParsed?.literal).filter(Boolean),
    license: bookLicense(project),
    // BOOK_PDF: the PDF of the book, relative to the site (scripts/build_site.py --pdf sets "book.pdf";
    // the PDF step writes it after this render). Without it no page links a PDF.
    pdf: process.env.BOOK_PDF || null,
    asset(route) {
      if (!pendingAssets.has(route)) pendingAssets.set(route, `assets/${path.posix.basename(route)}`);
      return pendingAssets.get(route);
    },
    fileAsset(name, content) {
      write(`assets/${name}`, content);
      return `assets/${name}`;
    },
    // A notebook page offers the executed notebook and the files of its `downloads` front matter
    // (scripts/build_site.py adds the paired percent script), next to it as in the repository.
    downloads(entry, fm) {
      const out = [];
      const exp = (fm.exports ?? []).find((x) => x.format === 'ipynb' && x.url);
      if (exp && entry.file.endsWith('.ipynb')) {
        const rel = entry.file; // e.g. notebooks/01_sparc.ipynb
        pendingAssets.set(exp.url, rel);
        entry.download = rel;
        out.push({ href: rel, name: path.posix.basename(rel), title: 'The notebook, executed' });
      }
      for (const d of fm.downloads ?? []) {
        if (!d.url || d.url === exp?.url) continue;
        const name = d.filename ?? path.posix.basename(d.url);
        const rel = path.posix.join(path.posix.dirname(entry.file), name);
        pendingAssets.set(d.url, rel);
        out.push({ href: rel, name, title: d.title ?? name });
      }
      entry.downloads = out.map((d) => d.href);
      return out;
    },
    build: {
      version: process.env.BOOK_VERSION || 'unversioned',
      commit: process.env.BOOK_COMMIT || 'unknown',
      date: process.env.BOOK_BUILD_DATE || new Date().toISOString().slice(0, 16).replace('T', ' ') + ' UTC',
    },
    previews: new Map(), // "page.html#id" -> hast nodes (collectPreviews)
  };

  // Two passes: render every article (collecting what cross-references can preview), then write
  // each page with the previews of the targets it refers to.
  const documents = [];
  const rendered = [];
  for (const entry of pages) {
    const data = contents.get(entry.slug);
    if (!data) continue;
    try {
      const page = new Page(site, entry, data);
      const article = page.render();
      collectPreviews(entry.href, article, site.previews);
      rendered.push({ entry, page, article });
      documents.push(...searchDocuments(entry, data));
    } catch (err) {
      failures.push(`page "${entry.file || entry.slug}" failed to render: ${err.stack ?? err}`);
    }
  }
  for (const { entry, page, article } of rendered) {
    try {
      const keys = [...page.xrefTargets].filter((k) => site.previews.has(k)).sort();
      write(entry.href, pageShell(site, entry, article, page.outline(), keys, page.description()));
    } catch (err) {
      failures.push(`page "${entry.file || entry.slug}" failed to render: ${err.stack ?? err}`);
    }
  }

  await Promise.all([...pendingAssets].map(async ([route, rel]) => {
    try {
      write(rel, await fetchFrom(route, 'binary'));
    } catch (err) {
      failures.push(`file ${route} (used as ${rel}): ${err.message}`);
    }
  }));

  // Search: the sections' text, shipped as a script that sets a global (search.js builds the index
  // from it in the browser, when the search box is first used).
  write('_static/search-index.js', `window.BOOK_SEARCH = ${JSON.stringify(searchIndexData(documents))};\n`);

  // Static files: theme CSS/JS, MiniSearch's browser build, KaTeX CSS with its woff2 fonts only.
  for (const f of fs.readdirSync(path.join(THEME, 'static'))) fs.copyFileSync(path.join(THEME, 'static', f), path.join(OUT, '_static', f));
  fs.copyFileSync(require_('minisearch/dist/umd/index.js'), path.join(OUT, '_static', 'minisearch.js'));
  const katexDist = require_('katex/dist');
  const css = fs.readFileSync(path.join(katexDist, 'katex.min.css'), 'utf8')
    .replace(/,url\(fonts\/[^)]+\.woff\) format\("woff"\),url\(fonts\/[^)]+\.ttf\) format\("truetype"\)/g, '');
  write('_static/katex/katex.min.css', css);
  for (const f of fs.readdirSync(path.join(katexDist, 'fonts')).filter((x) => x.endsWith('.woff2'))) {
    write(`_static/katex/fonts/${f}`, fs.readFileSync(path.join(katexDist, 'fonts', f)));
  }

  // The toc as data, for scripts/build_site.py and the tests: toc file -> page, notebook download.
  write('_static/pages.json', JSON.stringify({ title, build: site.build, pages: pages.map((p) => ({
    file: p.file, url: p.href, title: p.title, download: p.download ?? null, downloads: p.downloads ?? [] })) }, null, 1));

  for (const p of pages) {
    if (contents.has(p.slug) && !fs.existsSync(path.join(OUT, p.href))) failures.push(`page "${p.file}": ${p.href} was not written.`);
  }
  if (failures.length) fail(`the site is incomplete:\n  - ${failures.join('\n  - ')}`);
  process.stdout.write(`theme: wrote ${pages.length} pages, ${pendingAssets.size} files, ${documents.length} search sections to ${OUT} in ${((performance.now() - t0) / 1000).toFixed(1)} s\n`);
}

main().catch((err) => fail(err.stack ?? String(err)));
