// Sign in with a JSON POST (cross-site forms cannot send JSON without a CORS preflight).
import { languageSelect, t, translatePage } from "./i18n.js";

languageSelect(document.getElementById("ui-lang"));
translatePage();
document.getElementById("login-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  const body = {
    user: document.getElementById("user").value,
    password: document.getElementById("password").value,
  };
  const res = await fetch("/auth/login", {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
  });
  if (res.ok) {
    window.location.href = "/";
  } else {
    document.getElementById("login-error").textContent = t("wrong_login");
  }
});
