// The site's only script: the contents menu on narrow screens, search, the light/dark switch, copy
// buttons, the outline ("On this page") and hover previews of cross-references and citations.
// The search index is a global set by search-index.js (a <script>, since fetch() of file:// is
// blocked); MiniSearch comes from minisearch.js. Both are written by render.mjs.
(function () {
  'use strict';
  var root = document.documentElement;
  var WIDE = window.matchMedia('(min-width: 85.01rem)'); // the outline beside the text (theme.css)

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

  // ---- the scroll cue --------------------------------------------------------------------------------
  // A box that scrolls sideways (a long line of code or output, a wide table, a figure in its frame on a
  // phone) gets data-overflow = "right", "left" or "both": the edges where something is hidden, which
  // theme.css fades out. Updated when the box is scrolled or changes size.
  var SCROLLERS = 'main pre, main .table-wrap, main .output.html, main .image-frame, main .math-body';
  function markOverflow(el) {
    var hidden = el.scrollWidth - el.clientWidth;
    var state = '';
    if (hidden > 1) {
      var left = el.scrollLeft > 1, right = el.scrollLeft < hidden - 1;
      state = left && right ? 'both' : left ? 'left' : right ? 'right' : '';
    }
    if (state) el.setAttribute('data-overflow', state);
    else if (el.hasAttribute('data-overflow')) el.removeAttribute('data-overflow');
  }
  var scrollers = Array.prototype.slice.call(document.querySelectorAll(SCROLLERS));
  function markAll() { scrollers.forEach(markOverflow); }
  markAll();
  document.addEventListener('scroll', function (e) {
    if (e.target && e.target.matches && e.target.matches(SCROLLERS)) markOverflow(e.target);
  }, { passive: true, capture: true });
  if (window.ResizeObserver) {
    var sizes = new ResizeObserver(function (entries) { entries.forEach(function (en) { markOverflow(en.target); }); });
    scrollers.forEach(function (el) { sizes.observe(el); });
  } else {
    window.addEventListener('resize', markAll);
  }
  window.addEventListener('load', markAll); // images and fonts change widths

  // ---- figures at full size -------------------------------------------------------------------------
  // A click on a figure (or Enter / Space on it) shows it alone over the page: at its full resolution,
  // fitted to the window on desktop, at its drawn size on a phone (scrolled and pinch-zoomed there).
  // Escape, a click or the close button closes it and gives the focus back to the figure.
  var PHONE = window.matchMedia('(max-width: 40rem)');
  var overlay = null, opener = null;
  function closeFigure() {
    if (!overlay) return;
    overlay.remove();
    overlay = null;
    document.body.classList.remove('overlay-open');
    if (opener) opener.focus();
    opener = null;
  }
  function openFigure(img) {
    closeFigure();
    opener = img;
    overlay = document.createElement('div');
    overlay.className = 'figure-overlay';
    overlay.setAttribute('role', 'dialog');
    overlay.setAttribute('aria-modal', 'true');
    overlay.setAttribute('aria-label', 'The figure at full size' + (img.alt ? ': ' + img.alt.slice(0, 120) : ''));
    var big = document.createElement('img');
    big.src = img.currentSrc || img.src;
    big.alt = img.alt;
    // retina PNGs: naturalWidth device pixels = naturalWidth / 2 CSS px as drawn
    var drawn = img.getAttribute('width') ? Number(img.getAttribute('width')) : img.naturalWidth;
    var full = img.naturalWidth || drawn;
    var room = window.innerWidth - 32, roomY = window.innerHeight - 32;
    var w = PHONE.matches ? drawn : Math.max(Math.min(full, room, roomY * full / (img.naturalHeight || full)), Math.min(drawn, room));
    big.style.width = Math.round(w) + 'px';
    var close = document.createElement('button');
    close.type = 'button';
    close.setAttribute('aria-label', 'Close the figure');
    close.textContent = '×';
    overlay.appendChild(big);
    overlay.appendChild(close);
    overlay.addEventListener('click', function (e) {
      // on a phone, a tap on the image is for panning and zooming; elsewhere a click closes
      if (e.target === big && PHONE.matches) return;
      closeFigure();
    });
    overlay.addEventListener('keydown', function (e) { if (e.key === 'Tab') { e.preventDefault(); close.focus(); } });
    document.body.appendChild(overlay);
    document.body.classList.add('overlay-open');
    close.focus();
  }
  Array.prototype.forEach.call(document.querySelectorAll('main figure img, main img.output'), function (img) {
    if (img.closest('a')) return;
    img.classList.add('zoomable');
    img.tabIndex = 0;
    img.setAttribute('role', 'button');
    img.setAttribute('aria-label', 'Open the figure at full size' + (img.alt ? ': ' + img.alt.slice(0, 100) : ''));
  });
  document.addEventListener('click', function (e) {
    var img = e.target.closest && e.target.closest('img.zoomable');
    if (img) openFigure(img);
  });
  document.addEventListener('keydown', function (e) {
    if (e.key === 'Escape' && overlay) { closeFigure(); return; }
    var img = e.target.closest && e.target.closest('img.zoomable');
    if (img && (e.key === 'Enter' || e.key === ' ')) { e.preventDefault(); openFigure(img); }
  });

  // ---- print: folded code and outputs print open ----------------------------------------------------
  var PRINT = window.matchMedia('print');
  var opened = [];
  function openForPrint() {
    Array.prototype.forEach.call(document.querySelectorAll('main details:not([open])'), function (d) { d.open = true; opened.push(d); });
  }
  function restoreAfterPrint() {
    opened.forEach(function (d) { d.open = false; });
    opened = [];
  }
  window.addEventListener('beforeprint', openForPrint);
  window.addEventListener('afterprint', restoreAfterPrint);
  if (PRINT.addEventListener) PRINT.addEventListener('change', function (e) { if (e.matches) openForPrint(); else restoreAfterPrint(); });

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
