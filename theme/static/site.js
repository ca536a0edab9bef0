// The site's only script: the contents menu on narrow screens, search, the light/dark switch, copy
// buttons, the outline ("On this page") and hover previews of cross-references and citations.
// The search index is a global set by search-index.js (a <script>, since fetch() of file:// is
// blocked); MiniSearch comes from minisearch.js. Both are written by render.mjs.
(function () {
  'use strict';
  var root = document.documentElement;
  var WIDE = window.matchMedia('(min-width: 75rem)'); // the outline beside the text (theme.css)

  // ---- light / dark ------------------------------------------------------------------------------
  // No stored choice: the system setting (prefers-color-scheme, in theme.css). The button stores the
  // opposite of what is shown now; the <head> script applies a stored choice before the first paint.
  var DARK = window.matchMedia('(prefers-color-scheme: dark)');
  function currentTheme() { return root.dataset.theme || (DARK.matches ? 'dark' : 'light'); }
  var themeButton = document.getElementById('theme-toggle');
  function labelTheme() {
    if (!themeButton) return;
    var next = currentTheme() === 'dark' ? 'light' : 'dark';
    themeButton.setAttribute('aria-label', 'Switch to the ' + next + ' theme');
    themeButton.title = 'Switch to the ' + next + ' theme';
    themeButton.dataset.shows = currentTheme();
  }
  if (themeButton) {
    themeButton.addEventListener('click', function () {
      var next = currentTheme() === 'dark' ? 'light' : 'dark';
      root.dataset.theme = next;
      try { localStorage.setItem('book-theme', next); } catch (e) { /* storage blocked: this page only */ }
      labelTheme();
    });
    if (DARK.addEventListener) DARK.addEventListener('change', labelTheme);
    labelTheme();
  }

  // ---- contents menu (an overlay below the CSS breakpoint) ------------------------------------
  var toggle = document.getElementById('nav-toggle');
  var setOpen = function (open) {
    document.body.classList.toggle('nav-open', open);
    toggle.setAttribute('aria-expanded', String(open));
  };
  toggle.addEventListener('click', function () { setOpen(!document.body.classList.contains('nav-open')); });
  document.addEventListener('keydown', function (e) { if (e.key === 'Escape') setOpen(false); });
  document.querySelector('.layout').addEventListener('click', function (e) {
    if (document.body.classList.contains('nav-open') && !e.target.closest('.sidebar')) setOpen(false);
  });

  // ---- copy buttons ------------------------------------------------------------------------------
  function copyText(text) {
    if (navigator.clipboard && window.isSecureContext) return navigator.clipboard.writeText(text);
    return new Promise(function (resolve, reject) { // older browsers, or a context without the API
      var area = document.createElement('textarea');
      area.value = text;
      area.setAttribute('readonly', '');
      area.style.position = 'fixed';
      area.style.opacity = '0';
      document.body.appendChild(area);
      area.select();
      var ok = false;
      try { ok = document.execCommand('copy'); } catch (e) { ok = false; }
      document.body.removeChild(area);
      if (ok) resolve(); else reject(new Error('copy refused'));
    });
  }
  document.addEventListener('click', function (e) {
    var button = e.target.closest && e.target.closest('button.copy');
    if (!button) return;
    var pre = button.parentNode.querySelector('pre');
    if (!pre) return;
    var text = pre.textContent.replace(/\n$/, '');
    copyText(text).then(function () {
      button.textContent = 'Copied';
      button.classList.add('copied');
    }, function () {
      button.textContent = 'Press Ctrl+C';
      var range = document.createRange();
      range.selectNodeContents(pre);
      var sel = window.getSelection();
      sel.removeAllRanges();
      sel.addRange(range);
    });
    window.BOOK_LAST_COPY = text; // for the browser tests
    setTimeout(function () { button.textContent = 'Copy'; button.classList.remove('copied'); }, 1600);
  });

  // ---- outline: open beside the text on wide screens, mark the section in view ------------------
  var outline = document.querySelector('#outline details');
  if (outline) {
    var placeOutline = function () { outline.open = WIDE.matches; };
    placeOutline();
    if (WIDE.addEventListener) WIDE.addEventListener('change', placeOutline);
    outline.addEventListener('click', function (e) { // on a phone, jumping to a section closes it
      if (e.target.closest('a') && !WIDE.matches) outline.open = false;
    });
    var links = Array.prototype.slice.call(outline.querySelectorAll('a[href^="#"]'));
    var targets = links.map(function (a) { return document.getElementById(decodeURIComponent(a.getAttribute('href').slice(1))); });
    var marked = null;
    var mark = function () {
      // the last section whose heading has scrolled above a line a fifth down the window
      var line = window.innerHeight * 0.2;
      var index = -1;
      for (var i = 0; i < targets.length; i++) {
        if (targets[i] && targets[i].getBoundingClientRect().top <= line) index = i;
      }
      if (index < 0 && targets.length) index = 0;
      // at the end of the page the last sections cannot scroll up to the line: mark the last one in view
      if (window.innerHeight + window.scrollY >= document.documentElement.scrollHeight - 2) {
        for (var j = targets.length - 1; j > index; j--) {
          if (targets[j] && targets[j].getBoundingClientRect().top < window.innerHeight) { index = j; break; }
        }
      }
      var link = links[index] || null;
      if (link === marked) return;
      if (marked) { marked.classList.remove('active'); marked.removeAttribute('aria-current'); }
      marked = link;
      if (marked) {
        marked.classList.add('active');
        marked.setAttribute('aria-current', 'location');
        var nav = outline.parentNode; // the scrolling column beside the text
        if (WIDE.matches && nav.scrollHeight > nav.clientHeight) {
          var box = nav.getBoundingClientRect(), r = marked.getBoundingClientRect();
          if (r.top < box.top || r.bottom > box.bottom) nav.scrollTop += r.top - box.top - box.height / 2;
        }
      }
    };
    var pending = false;
    window.addEventListener('scroll', function () {
      if (pending) return;
      pending = true;
      window.requestAnimationFrame(function () { pending = false; mark(); });
    }, { passive: true });
    window.addEventListener('resize', mark);
    mark();
  }

  // ---- hover previews ----------------------------------------------------------------------------
  // A cross-reference shows its target (figure, equation, section) from the <template data-xref> the
  // page carries; a citation shows its entry of the page's reference list.
  var popup = null, popupFor = null, hideTimer = null;
  function previewContent(a) {
    if (a.classList.contains('xref')) {
      var key = a.getAttribute('data-xref');
      var tpl = key && document.querySelector('template[data-xref="' + key.replace(/"/g, '\\"') + '"]');
      return tpl ? tpl.content.cloneNode(true) : null;
    }
    if (a.classList.contains('cite')) {
      var entry = document.getElementById(decodeURIComponent((a.getAttribute('href') || '').slice(1)));
      if (!entry) return null;
      var frag = document.createDocumentFragment();
      var p = document.createElement('p');
      p.innerHTML = entry.innerHTML;
      frag.appendChild(p);
      return frag;
    }
    return null;
  }
  function hidePreview() {
    if (popup) popup.remove();
    if (popupFor) popupFor.removeAttribute('aria-describedby');
    popup = null;
    popupFor = null;
  }
  function showPreview(a) {
    clearTimeout(hideTimer);
    if (popupFor === a) return;
    hidePreview();
    var content = previewContent(a);
    if (!content) return;
    popup = document.createElement('div');
    popup.className = 'preview' + (a.classList.contains('cite') ? ' preview-cite' : '');
    popup.id = 'preview-popup';
    popup.setAttribute('role', 'tooltip');
    popup.appendChild(content);
    popup.addEventListener('mouseenter', function () { clearTimeout(hideTimer); });
    popup.addEventListener('mouseleave', scheduleHide);
    document.body.appendChild(popup);
    popupFor = a;
    a.setAttribute('aria-describedby', 'preview-popup');
    var r = a.getBoundingClientRect();
    var width = Math.min(popup.offsetWidth, window.innerWidth - 16);
    var left = Math.max(8, Math.min(r.left + window.scrollX, window.scrollX + window.innerWidth - width - 8));
    var below = r.bottom + 8 + popup.offsetHeight < window.innerHeight || r.top < popup.offsetHeight + 8;
    popup.style.left = left + 'px';
    popup.style.top = (below ? r.bottom + window.scrollY + 6 : r.top + window.scrollY - popup.offsetHeight - 6) + 'px';
  }
  function scheduleHide() {
    clearTimeout(hideTimer);
    hideTimer = setTimeout(hidePreview, 250);
  }
  function previewLink(e) { return e.target.closest && e.target.closest('a.xref[data-xref], a.cite'); }
  document.addEventListener('mouseover', function (e) { var a = previewLink(e); if (a) showPreview(a); });
  document.addEventListener('mouseout', function (e) { var a = previewLink(e); if (a) scheduleHide(); });
  document.addEventListener('focusin', function (e) { var a = previewLink(e); if (a) showPreview(a); });
  document.addEventListener('focusout', function (e) { var a = previewLink(e); if (a) scheduleHide(); });
  document.addEventListener('keydown', function (e) { if (e.key === 'Escape') hidePreview(); });
  window.addEventListener('scroll', function () { if (popup && !popup.matches(':hover')) hidePreview(); }, { passive: true });

  // ---- search: search.js (the box's results); "/" focuses the box ----------------------------------
  var input = document.getElementById('search-input');
  // "/" focuses the search box, as on many documentation sites.
  document.addEventListener('keydown', function (e) {
    if (e.key === '/' && document.activeElement !== input && !/INPUT|TEXTAREA/.test(document.activeElement.tagName)) {
      e.preventDefault();
      if (window.matchMedia('(max-width: 60rem)').matches) setOpen(true);
      input.focus();
    }
  });
})();
