// Injected at the end of a copy of report.html by check_report.sh: measures the page as
// the browser laid it out and writes the findings into the DOM (<pre id="layout-check">),
// which `chromium --headless --dump-dom` then prints.
(function () {
  const W = window.innerWidth;
  const out = { innerWidth: W, scrollWidth: document.documentElement.scrollWidth,
                outside: [], overflowing: [], clipped: [], overlapping: [], covered: [] };
  const name = (e) => e.tagName.toLowerCase() + ": " + (e.textContent || "").trim().slice(0, 60);
  // HTML boxes: past the right edge of the page, or content wider than the box
  for (const e of document.body.querySelectorAll("*")) {
    if (e.closest("svg") && e.tagName.toLowerCase() !== "svg") continue;
    const r = e.getBoundingClientRect();
    if (r.width > 0 && r.right > W + 1) out.outside.push(name(e) + " (right edge " + Math.round(r.right) + " px)");
    if (e.tagName.toLowerCase() !== "svg" && e.clientWidth > 0 && e.scrollWidth > e.clientWidth + 1)
      out.overflowing.push(name(e) + " (" + e.scrollWidth + " px in " + e.clientWidth + ")");
  }
  for (const svg of document.querySelectorAll("svg")) {
    const s = svg.getBoundingClientRect();
    const texts = Array.from(svg.querySelectorAll("text")).filter((t) => t.textContent.trim());
    const boxes = texts.map((t) => t.getBoundingClientRect());
    // text cut by the edge of its picture
    texts.forEach((t, i) => {
      const r = boxes[i];
      if (r.left < s.left - 1 || r.right > s.right + 1 || r.top < s.top - 1 || r.bottom > s.bottom + 1)
        out.clipped.push("'" + t.textContent + "' in '" + (svg.querySelector("text") || {}).textContent + "'");
    });
    // two texts drawn over each other (more than 2 px both ways)
    for (let i = 0; i < boxes.length; i++)
      for (let j = i + 1; j < boxes.length; j++) {
        const a = boxes[i], b = boxes[j];
        const dx = Math.min(a.right, b.right) - Math.max(a.left, b.left);
        const dy = Math.min(a.bottom, b.bottom) - Math.max(a.top, b.top);
        if (dx > 2 && dy > 2) out.overlapping.push("'" + texts[i].textContent + "' / '" + texts[j].textContent + "'");
      }
    // data markers under a legend entry
    const legend = Array.from(svg.querySelectorAll(".legend text, .legend rect")).map((e) => e.getBoundingClientRect());
    for (const c of svg.querySelectorAll(".series circle")) {
      const p = c.getBoundingClientRect();
      const x = (p.left + p.right) / 2, y = (p.top + p.bottom) / 2;
      if (legend.some((r) => x >= r.left && x <= r.right && y >= r.top && y <= r.bottom))
        out.covered.push("a point of '" + c.parentNode.getAttribute("data-label") + "'");
    }
  }
  // numbers printed with more digits than they mean (a rate of 0.7582325275954309)
  out.long_numbers = [];
  const walk = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n = walk.nextNode(); n; n = walk.nextNode()) {
    if (n.parentNode.closest("script")) continue;
    for (const m of n.textContent.match(/\d+\.\d{7,}/g) || []) out.long_numbers.push(m);
  }
  const pre = document.createElement("pre");
  pre.id = "layout-check";
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
})();
