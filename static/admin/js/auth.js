/**
 * The admin token, kept in this tab's sessionStorage only (closing the tab logs out; it is never put in
 * the address or in localStorage). The server checks it on every call; the dashboard shows nothing but
 * the login form until the server has accepted it.
 */

const KEY = "steakhouse.admin.token";

export function storedToken() {
  try {
    return window.sessionStorage.getItem(KEY) || "";
  } catch {
    return "";
  }
}

export function storeToken(token) {
  try {
    window.sessionStorage.setItem(KEY, token);
  } catch {
    /* storage disabled: the token lives in memory until the page is closed */
  }
}

export function forgetToken() {
  try {
    window.sessionStorage.removeItem(KEY);
  } catch {
    /* nothing stored */
  }
}
