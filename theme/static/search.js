// The search box. Nothing is loaded until the box is first focused or typed in: then MiniSearch
// (minisearch.js) and the sections' text (search-index.js, which sets window.BOOK_SEARCH; render.mjs
// writes both) come as <script> tags, since fetch() of file:// is blocked, and the index is built
// here. Scripts the page already loaded are used as they are. Results are grouped by page, chapters
// ranked above the other pages and those above API entries; each section shows a snippet of its text
// with the query's words marked. ArrowDown/ArrowUp choose a result, Enter opens it (the first one
// unless another was chosen), Escape closes the list (a second Escape clears the box).
(function () {
  'use strict';
  var input = document.getElementById('search-input');
  var list = document.getElementById('search-results');
  if (!input || !list) return;
  var box = input.parentNode;
  // The folder of this script (_static/): the two files loaded on first use are beside it.
  var here = document.currentScript && document.currentScript.getAttribute('src');
  var base = here ? here.replace(/[^/]*$/, '') : '_static/';

  var KIND_BOOST = { chapter: 1, docs: 0.6, api: 0.2 }; // multiplies a section's score, by its page's kind
  var KIND_LABEL = { api: 'API' };
  var MIN_QUERY = 2, MAX_PAGES = 8, MAX_PER_PAGE = 4, SNIPPET = 170, LEAD = 55;
  var searchOptions = {
    prefix: function (term) { return term.length >= 2; },
    fuzzy: function (term) { return term.length >= 5 ? 0.2 : false; }, // "dask" must not find "task"
    combineWith: 'AND',
    boost: { page: 4, section: 2.5 },
    boostDocument: function (id) { return KIND_BOOST[kindOf(id)] || 1; },
  };

  var state = 'idle'; // idle -> loading -> ready | failed
  var data = null, mini = null;
  var options = [], selected = -1, openWhenReady = false;

  // Screen readers: the box is a combobox whose list is a listbox of options grouped by page.
  input.setAttribute('role', 'combobox');
  input.setAttribute('aria-autocomplete', 'list');
  input.setAttribute('aria-controls', list.id);
  input.setAttribute('aria-expanded', 'false');
  list.setAttribute('role', 'listbox');
  list.setAttribute('aria-label', 'Search results');
  list.removeAttribute('aria-live');
  var status = document.createElement('div');
  status.className = 'visually-hidden';
  status.setAttribute('role', 'status');
  box.appendChild(status);

  // ---- loading on first use ------------------------------------------------------------------------
  function loadScript(name, isLoaded, done) {
    if (isLoaded()) { done(true); return; }
    var script = document.createElement('script');
    script.src = base + name;
    script.onload = function () { done(isLoaded()); };
    script.onerror = function () { done(false); };
    document.head.appendChild(script);
  }

  function ensureIndex() {
    if (state !== 'idle') return;
    state = 'loading';
    var pending = 2, ok = true;
    var done = function (loaded) {
      ok = ok && loaded;
      if (--pending) return;
      try {
        if (!ok) throw new Error('search files not loaded');
        buildIndex();
        state = 'ready';
      } catch (e) {
        state = 'failed';
      }
      show(input.value);
    };
    loadScript('minisearch.js', function () { return !!window.MiniSearch; }, done);
    loadScript('search-index.js', function () { return !!window.BOOK_SEARCH; }, done);
  }

  function buildIndex() {
    data = window.BOOK_SEARCH;
    var fields = (data.options && data.options.fields) || ['page', 'section', 'text'];
    mini = new window.MiniSearch({ fields: fields, storeFields: [] });
    // The page's title is indexed with its first section only: a page about the query leads with its
    // opening, and its other sections rank by their own text.
    mini.addAll(data.sections.map(function (s, i) {
      var first = i === 0 || data.sections[i - 1][0] !== s[0];
      return { id: i, page: first ? data.pages[s[0]].title : '', section: s[1], text: s[3] };
    }));
    window.BOOK_SEARCH_READY = true; // for the browser tests
  }

  function kindOf(id) { return data.pages[data.sections[id][0]].kind; }

  // ---- ranking and grouping --------------------------------------------------------------------------
  // Sections in score order, gathered by page; pages ordered by their best section.
  function grouped(query) {
    var results = mini.search(query, searchOptions);
    var partial = false;
    if (!results.length && /\s/.test(query.trim())) { // no section has every word: those with some
      var any = {};
      for (var k in searchOptions) any[k] = searchOptions[k];
      any.combineWith = 'OR';
      results = mini.search(query, any);
      partial = results.length > 0;
    }
    var groups = [], byPage = {};
    results.forEach(function (r) {
      var s = data.sections[r.id];
      var g = byPage[s[0]];
      if (!g) {
        if (groups.length >= MAX_PAGES) return;
        g = byPage[s[0]] = { page: data.pages[s[0]], hits: [], more: 0 };
        groups.push(g);
      }
      if (g.hits.length < MAX_PER_PAGE) g.hits.push({ section: s, terms: r.terms });
      else g.more++;
    });
    return { groups: groups, partial: partial, total: results.length };
  }

  // ---- snippets ---------------------------------------------------------------------------------------
  // MiniSearch splits words at spaces and punctuation; a term is marked where it is a whole word so.
  var SEPARATOR;
  try { SEPARATOR = new RegExp('[\\n\\r\\p{Z}\\p{P}]', 'u'); } catch (e) { SEPARATOR = /[\s!-/:-@[-`{-~]/; }
  function isEdge(text, i) { return i < 0 || i >= text.length || SEPARATOR.test(text.charAt(i)); }

  function occurrences(text, terms) {
    var lower = text.toLowerCase();
    if (lower.length !== text.length) lower = text; // a letter whose lower case is longer: match as written
    var hits = [];
    terms.forEach(function (term, t) {
      if (!term) return;
      var at = lower.indexOf(term);
      while (at !== -1) {
        if (isEdge(lower, at - 1) && isEdge(lower, at + term.length)) hits.push({ start: at, end: at + term.length, term: t });
        at = lower.indexOf(term, at + term.length);
      }
    });
    return hits.sort(function (a, b) { return a.start - b.start || b.end - a.end; });
  }

  // The window of the text that holds the most different query words, from a little before the first.
  function snippetRange(text, hits) {
    if (text.length <= SNIPPET) return [0, text.length];
    var best = null;
    hits.forEach(function (h) {
      var from = Math.max(0, h.start - LEAD), to = from + SNIPPET, seen = {}, n = 0;
      hits.forEach(function (o) { if (o.start >= from && o.end <= to && !seen[o.term]) { seen[o.term] = true; n++; } });
      if (!best || n > best.n) best = { n: n, from: from };
    });
    var from = best ? best.from : 0;
    var to = Math.min(text.length, from + SNIPPET);
    if (to === text.length) from = Math.max(0, to - SNIPPET);
    if (from > 0) { var sp = text.indexOf(' ', from); if (sp !== -1 && sp < from + 20) from = sp + 1; }
    if (to < text.length) { var ep = text.lastIndexOf(' ', to); if (ep > to - 20) to = ep; }
    return [from, to];
  }

  // A fragment of text[from, to) with the hits inside it in <mark>.
  function marked(text, hits, from, to) {
    var frag = document.createDocumentFragment();
    var at = from;
    hits.forEach(function (h) {
      if (h.start < at || h.end > to) return;
      if (h.start > at) frag.appendChild(document.createTextNode(text.slice(at, h.start)));
      var m = document.createElement('mark');
      m.textContent = text.slice(h.start, h.end);
      frag.appendChild(m);
      at = h.end;
    });
    if (at < to) frag.appendChild(document.createTextNode(text.slice(at, to)));
    return frag;
  }

  function span(className, content) {
    var el = document.createElement('span');
    el.className = className;
    if (typeof content === 'string') el.textContent = content; else el.appendChild(content);
    return el;
  }

  // ---- the list --------------------------------------------------------------------------------------
  function note(text) {
    var li = document.createElement('li');
    li.className = 'search-none';
    li.setAttribute('role', 'presentation');
    li.textContent = text;
    list.appendChild(li);
  }

  function setOpen(open) {
    list.hidden = !open;
    input.setAttribute('aria-expanded', String(open));
    document.body.classList.toggle('search-open', open); // lifts the sidebar above the text (theme.css)
    if (!open) select(-1);
  }

  function show(query) {
    var q = query.trim();
    list.textContent = '';
    options = [];
    selected = -1;
    input.removeAttribute('aria-activedescendant');
    if (q.length < MIN_QUERY) { setOpen(false); status.textContent = ''; return; }
    if (state !== 'ready') {
      note(state === 'failed' ? 'The search index could not be loaded.' : 'Loading the search index…');
      setOpen(true);
      if (state === 'idle') ensureIndex();
      return;
    }
    var found = grouped(q);
    if (!found.groups.length) {
      note('Nothing found for “' + q + '”.');
      status.textContent = 'Nothing found.';
      setOpen(true);
      return;
    }
    if (found.partial) note('No section has all the words; sections with some of them:');
    found.groups.forEach(function (g, gi) {
      var li = document.createElement('li');
      li.className = 'search-group search-kind-' + g.page.kind;
      li.setAttribute('role', 'group');
      var title = document.createElement('div');
      title.className = 'search-page';
      title.id = 'search-group-' + gi;
      title.textContent = g.page.title;
      if (KIND_LABEL[g.page.kind]) title.appendChild(span('search-kind', KIND_LABEL[g.page.kind]));
      li.setAttribute('aria-labelledby', title.id);
      li.appendChild(title);
      var ul = document.createElement('ul');
      ul.setAttribute('role', 'presentation');
      g.hits.forEach(function (hit) {
        var s = hit.section, text = s[3], heading = s[1] || g.page.title;
        var a = document.createElement('a');
        a.className = 'search-result';
        a.href = g.page.url + (s[2] ? '#' + s[2] : '');
        a.id = 'search-option-' + options.length;
        a.setAttribute('role', 'option');
        a.setAttribute('aria-selected', 'false');
        a.tabIndex = -1;
        a.appendChild(span('search-section', marked(heading, occurrences(heading, hit.terms), 0, heading.length)));
        if (text) {
          var hits = occurrences(text, hit.terms);
          var range = snippetRange(text, hits);
          var snip = span('search-snippet', marked(text, hits, range[0], range[1]));
          if (range[0] > 0) snip.insertBefore(document.createTextNode('…'), snip.firstChild);
          if (range[1] < text.length) snip.appendChild(document.createTextNode('…'));
          a.appendChild(snip);
        }
        var item = document.createElement('li');
        item.setAttribute('role', 'presentation');
        item.appendChild(a);
        ul.appendChild(item);
        options.push(a);
      });
      li.appendChild(ul);
      if (g.more) {
        var more = document.createElement('div');
        more.className = 'search-more';
        more.textContent = '+ ' + g.more + ' more section' + (g.more > 1 ? 's' : '') + ' of this page';
        li.appendChild(more);
      }
      list.appendChild(li);
    });
    status.textContent = found.total + (found.total > 1 ? ' sections' : ' section') + ' found; ' + options.length +
      ' listed, from ' + found.groups.length + (found.groups.length > 1 ? ' pages' : ' page') + '. The first: ' +
      options[0].querySelector('.search-section').textContent + ', in ' + found.groups[0].page.title + '.';
    setOpen(true);
    select(0);
    if (openWhenReady) { openWhenReady = false; open(options[0]); }
  }

  function select(i) {
    if (selected >= 0 && options[selected]) {
      options[selected].classList.remove('selected');
      options[selected].setAttribute('aria-selected', 'false');
    }
    selected = i;
    if (i < 0 || !options[i]) { input.removeAttribute('aria-activedescendant'); return; }
    var a = options[i];
    a.classList.add('selected');
    a.setAttribute('aria-selected', 'true');
    input.setAttribute('aria-activedescendant', a.id);
    if (list.scrollHeight > list.clientHeight) a.scrollIntoView({ block: 'nearest' });
  }

  // Going to a result closes the list, and on a phone the contents menu around it (site.js's button),
  // so that a section of this same page is not left behind the menu.
  function leave() {
    setOpen(false);
    var menu = document.getElementById('nav-toggle');
    if (menu && document.body.classList.contains('nav-open')) menu.click();
  }

  function open(a) {
    leave();
    window.location.href = a.href;
  }

  // ---- events ---------------------------------------------------------------------------------------
  input.addEventListener('focus', function () {
    ensureIndex();
    if (input.value.trim().length >= MIN_QUERY && list.hidden) show(input.value);
  });
  input.addEventListener('input', function () { openWhenReady = false; ensureIndex(); show(input.value); });
  input.addEventListener('keydown', function (e) {
    var n = options.length;
    if (e.key === 'ArrowDown' || e.key === 'ArrowUp') {
      if (list.hidden && input.value.trim().length >= MIN_QUERY) show(input.value);
      if (!options.length) return;
      e.preventDefault();
      n = options.length;
      select(e.key === 'ArrowDown' ? (selected + 1) % n : (selected - 1 + n) % n);
    } else if (e.key === 'Enter') {
      e.preventDefault();
      if (selected >= 0 && options[selected] && !list.hidden) open(options[selected]);
      else if (n && !list.hidden) open(options[0]);
      else if (state !== 'ready' && input.value.trim().length >= MIN_QUERY) openWhenReady = true;
    } else if (e.key === 'Escape') {
      // Only the list closes (not the contents menu around the box on a phone), and the query stays
      // (a search box clears itself on Escape): a second Escape clears it.
      e.stopPropagation();
      e.preventDefault();
      if (!list.hidden) setOpen(false);
      else { input.value = ''; show(''); }
    }
  });
  list.addEventListener('mousemove', function (e) {
    var a = e.target.closest && e.target.closest('a.search-result');
    var i = options.indexOf(a);
    if (i >= 0 && i !== selected) select(i);
  });
  list.addEventListener('click', function (e) {
    if (e.target.closest && e.target.closest('a.search-result')) leave();
  });
  // A click or focus elsewhere closes the list.
  document.addEventListener('mousedown', function (e) { if (!box.contains(e.target)) setOpen(false); });
  document.addEventListener('focusin', function (e) { if (!box.contains(e.target)) setOpen(false); });
})();
