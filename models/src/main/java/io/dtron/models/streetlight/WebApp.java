package io.dtron.models.streetlight;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.security.SecureRandom;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.TimeUnit;
import org.eclipse.jetty.http.HttpCookie;
import org.eclipse.jetty.http.HttpHeader;
import org.eclipse.jetty.http.HttpStatus;
import org.eclipse.jetty.server.Handler;
import org.eclipse.jetty.server.Request;
import org.eclipse.jetty.server.Response;
import org.eclipse.jetty.util.Callback;
import org.eclipse.jetty.util.Fields;

/**
 * The street-light web application: server-rendered pages with stable element ids and labels, sessions by
 * cookie, and the API the controllers poll. Logging in starts an empty workspace: no controller ticked, no
 * command. With the session mix-up switch on, the workspace (the ticked controllers and the last command) is kept
 * in one place for all sessions instead of in each session, as a bean of the wrong scope would: concurrent
 * operators switch and see each other's controllers, and a login empties everyone's workspace.
 */
final class WebApp extends Handler.Abstract {
    static final String COOKIE = "SLSESSION";
    private static final long NOK_AFTER_NANOS = TimeUnit.SECONDS.toNanos(3);

    private final Controllers controllers;
    private final boolean sessionMixUp;
    private final Map<String, Session> sessions = new ConcurrentHashMap<>();
    private final Workspace shared = new Workspace();
    private final SecureRandom random = new SecureRandom();

    WebApp(Controllers controllers, boolean sessionMixUp) {
        super(InvocationType.BLOCKING);
        this.controllers = controllers;
        this.sessionMixUp = sessionMixUp;
    }

    /** A command of one controller: the state requested and when. */
    private record Command(int controller, LightState state, long nanos) {
    }

    /** What an operator works on: the controllers it ticked and the commands of its last switch. */
    private static final class Workspace {
        private List<Integer> selection = List.of();
        private List<Command> lastCommands = List.of();

        synchronized List<Integer> selection() {
            return selection;
        }

        synchronized void select(List<Integer> ids) {
            selection = List.copyOf(ids);
        }

        synchronized List<Command> lastCommands() {
            return lastCommands;
        }

        synchronized void commanded(List<Command> commands) {
            lastCommands = List.copyOf(commands);
        }

        synchronized void clear() {
            selection = List.of();
            lastCommands = List.of();
        }
    }

    /** A logged-in operator. */
    private record Session(String user, Workspace own) {
    }

    @Override
    public boolean handle(Request request, Response response, Callback callback) throws Exception {
        String path = Request.getPathInContext(request);
        boolean post = request.getMethod().equals("POST");
        if (path.equals("/api/poll")) {
            poll(request, response, callback);
            return true;
        }
        if (path.equals("/login")) {
            if (post) {
                login(request, response, callback);
            } else {
                html(response, callback, HttpStatus.OK_200, loginPage(""));
            }
            return true;
        }
        Optional<Session> session = session(request);
        if (path.equals("/logout")) {
            cookie(request).ifPresent(sessions::remove);
            Response.addCookie(response, HttpCookie.build(COOKIE, "").path("/").maxAge(0).build());
            redirect(request, response, callback, "/login");
            return true;
        }
        if (session.isEmpty()) {
            redirect(request, response, callback, "/login");
            return true;
        }
        Session s = session.get();
        Workspace work = workspace(s);
        switch (path) {
            case "/":
                redirect(request, response, callback, "/home");
                break;
            case "/home":
                html(response, callback, HttpStatus.OK_200, page("Home", s, "<h1>Welcome, " + escape(s.user())
                        + "</h1>\n<p>Open the list of light controllers from the menu to switch them.</p>"));
                break;
            case "/controllers":
                html(response, callback, HttpStatus.OK_200, controllersPage(s, ""));
                break;
            case "/select":
                select(request, response, callback, s, work, post);
                break;
            case "/command":
                html(response, callback, HttpStatus.OK_200, commandPage(s, work, ""));
                break;
            case "/switch":
                switchLights(request, response, callback, s, work, post);
                break;
            case "/result":
                html(response, callback, HttpStatus.OK_200, resultPage(s, work));
                break;
            default:
                html(response, callback, HttpStatus.NOT_FOUND_404, page("Not found", s,
                        "<h1>Not found</h1>\n<p>There is no page " + escape(path) + ".</p>"));
        }
        return true;
    }

    private void login(Request request, Response response, Callback callback) throws Exception {
        Fields fields = Request.getParameters(request);
        String user = value(fields, "username");
        String password = value(fields, "password");
        if (!user.matches("user\\d{1,2}") || !password.equals(StreetLightServer.PASSWORD)) {
            html(response, callback, HttpStatus.OK_200, loginPage("Wrong user name or password."));
            return;
        }
        byte[] bytes = new byte[16];
        random.nextBytes(bytes);
        String id = HexFormat.of().formatHex(bytes);
        Session session = new Session(user, new Workspace());
        sessions.put(id, session);
        workspace(session).clear();
        Response.addCookie(response, HttpCookie.build(COOKIE, id).path("/").httpOnly(true).build());
        redirect(request, response, callback, "/home");
    }

    private void select(Request request, Response response, Callback callback, Session s, Workspace work,
                        boolean post) throws Exception {
        if (!post) {
            redirect(request, response, callback, "/controllers");
            return;
        }
        List<Integer> ids = new ArrayList<>();
        for (String value : Request.getParameters(request).getValuesOrEmpty("controller")) {
            Integer id = parseInt(value);
            if (id == null || !controllers.exists(id)) {
                html(response, callback, HttpStatus.BAD_REQUEST_400, controllersPage(s, "No controller "
                        + escape(value) + "."));
                return;
            }
            ids.add(id);
        }
        if (ids.isEmpty()) {
            html(response, callback, HttpStatus.OK_200, controllersPage(s, "Tick at least one controller."));
            return;
        }
        work.select(ids);
        redirect(request, response, callback, "/command");
    }

    private void switchLights(Request request, Response response, Callback callback, Session s, Workspace work,
                              boolean post) throws Exception {
        if (!post) {
            redirect(request, response, callback, "/command");
            return;
        }
        List<Integer> selection = work.selection();
        if (selection.isEmpty()) {
            redirect(request, response, callback, "/controllers");
            return;
        }
        Optional<LightState> state = LightState.parse(value(Request.getParameters(request), "state"));
        if (state.isEmpty()) {
            html(response, callback, HttpStatus.OK_200, commandPage(s, work, "Choose a state."));
            return;
        }
        List<Command> commands = new ArrayList<>();
        long now = System.nanoTime();
        for (int id : selection) {
            controllers.request(id, state.get());
            commands.add(new Command(id, state.get(), now));
        }
        work.commanded(commands);
        redirect(request, response, callback, "/result");
    }

    private void poll(Request request, Response response, Callback callback) {
        Map<String, String> status;
        try {
            status = VirtualController.decode(value(Request.extractQueryParameters(request), "status"));
        } catch (IllegalArgumentException e) {
            text(response, callback, HttpStatus.BAD_REQUEST_400, "malformed status: " + e.getMessage());
            return;
        }
        Integer id = parseInt(status.getOrDefault("id", ""));
        Optional<LightState> state = LightState.parse(status.getOrDefault("state", ""));
        if (id == null || !controllers.exists(id) || state.isEmpty()) {
            text(response, callback, HttpStatus.BAD_REQUEST_400, "unknown controller or state in " + status);
            return;
        }
        LightState requested = controllers.report(id, state.get());
        text(response, callback, HttpStatus.OK_200, VirtualController.encode(Map.of("command", requested.name())));
    }

    /** What the operator of a session works on: its own, or with the mix-up the one all sessions share. */
    private Workspace workspace(Session session) {
        return sessionMixUp ? shared : session.own();
    }

    private Optional<Session> session(Request request) {
        return cookie(request).map(sessions::get);
    }

    private static Optional<String> cookie(Request request) {
        return Request.getCookies(request).stream().filter(c -> c.getName().equals(COOKIE))
                .map(HttpCookie::getValue).findFirst();
    }

    private static String loginPage(String error) {
        return layout("Log in", "", "<h1>Log in</h1>\n" + error(error, "login-error")
                + "<form id=\"login-form\" method=\"post\" action=\"/login\">\n"
                + "<p><label for=\"username\">User name</label> <input id=\"username\" name=\"username\""
                + " autocomplete=\"off\"></p>\n"
                + "<p><label for=\"password\">Password</label> <input id=\"password\" name=\"password\""
                + " type=\"password\"></p>\n"
                + "<p><button id=\"login-button\" type=\"submit\">Log in</button></p>\n</form>");
    }

    private String controllersPage(Session s, String error) {
        StringBuilder rows = new StringBuilder();
        for (int id = 0; id < controllers.count(); id++) {
            rows.append("<tr id=\"controller-").append(id).append("\"><td><input type=\"checkbox\" id=\"ctrl-")
                    .append(id).append("\" name=\"controller\" value=\"").append(id).append("\"></td>")
                    .append("<td><label for=\"ctrl-").append(id).append("\">Controller ").append(id)
                    .append("</label></td><td>").append(escape(controllers.place(id)))
                    .append("</td><td class=\"state\">").append(controllers.reported(id).state().label())
                    .append("</td></tr>\n");
        }
        return page("Controllers", s, "<h1>Controllers</h1>\n" + error(error, "select-error")
                + "<form id=\"controller-list\" method=\"post\" action=\"/select\">\n"
                + "<table id=\"controllers\"><thead><tr><th></th><th>Controller</th><th>Place</th><th>Lamps</th>"
                + "</tr></thead><tbody>\n" + rows + "</tbody></table>\n"
                + "<p><button id=\"select-button\" type=\"submit\">Select</button></p>\n</form>");
    }

    private static String commandPage(Session s, Workspace work, String error) {
        List<Integer> selection = work.selection();
        if (selection.isEmpty()) {
            return page("Switch", s, "<h1>Switch</h1>\n<p id=\"no-selection\">Select controllers in the list"
                    + " first.</p>");
        }
        StringBuilder radios = new StringBuilder();
        for (LightState state : LightState.values()) {
            String id = "state-" + state.name().toLowerCase(Locale.ROOT);
            radios.append("<p><input type=\"radio\" id=\"").append(id).append("\" name=\"state\" value=\"")
                    .append(state.name()).append("\"><label for=\"").append(id).append("\">").append(state.label())
                    .append("</label></p>\n");
        }
        return page("Switch", s, "<h1>Switch</h1>\n" + error(error, "switch-error")
                + "<p id=\"selected\">Selected: " + String.join(", ", selection.stream()
                .map(id -> "Controller " + id).toList()) + "</p>\n"
                + "<form id=\"command-form\" method=\"post\" action=\"/switch\">\n"
                + "<fieldset><legend>New state</legend>\n" + radios + "</fieldset>\n"
                + "<p><button id=\"switch-button\" type=\"submit\">Switch</button></p>\n</form>");
    }

    private String resultPage(Session s, Workspace work) {
        List<Command> commands = work.lastCommands();
        if (commands.isEmpty()) {
            return page("Result", s, "<h1>Result</h1>\n<p id=\"no-result\">No command yet.</p>");
        }
        StringBuilder rows = new StringBuilder();
        long now = System.nanoTime();
        for (Command c : commands) {
            Controllers.Report report = controllers.reported(c.controller());
            String status;
            LightState shown;
            if (report.nanos() - c.nanos() > 0 && report.state() == c.state()) {
                status = "OK";
                shown = report.state();
            } else if (now - c.nanos() > NOK_AFTER_NANOS) {
                status = "NOK";
                shown = report.state();
            } else {
                status = "PENDING";
                shown = c.state();
            }
            rows.append("<tr id=\"result-").append(c.controller()).append("\"><td class=\"controller\">")
                    .append(c.controller()).append("</td><td class=\"state\">").append(shown.label())
                    .append("</td><td class=\"status\">").append(status).append("</td></tr>\n");
        }
        return page("Result", s, "<h1>Result</h1>\n<table id=\"results\"><thead><tr><th>Controller</th>"
                + "<th>State</th><th>Status</th></tr></thead><tbody>\n" + rows + "</tbody></table>\n"
                + "<p><a id=\"refresh-link\" href=\"/result\">Refresh</a></p>");
    }

    private static String page(String title, Session s, String body) {
        return layout(title, "<p id=\"session\">Logged in as <b id=\"current-user\">" + escape(s.user())
                + "</b></p>\n<nav><a id=\"controllers-link\" href=\"/controllers\">Controllers</a>"
                + " <a id=\"logout-link\" href=\"/logout\">Log out</a></nav>\n", body);
    }

    private static String layout(String title, String header, String body) {
        return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Street lights - "
                + escape(title) + "</title>\n<style>body{font-family:sans-serif;margin:2em}"
                + "td,th{padding:0.2em 1em;text-align:left}.error{color:#b00}</style></head>\n<body>\n<header>"
                + "<p><b>Street lights</b></p>\n" + header + "</header>\n<main>\n" + body
                + "\n</main>\n</body></html>\n";
    }

    private static String error(String error, String id) {
        return error.isEmpty() ? "" : "<p id=\"" + id + "\" class=\"error\">" + error + "</p>\n";
    }

    private static void html(Response response, Callback callback, int status, String html) {
        write(response, callback, status, "text/html; charset=utf-8", html);
    }

    private static void text(Response response, Callback callback, int status, String text) {
        write(response, callback, status, "text/plain; charset=utf-8", text);
    }

    private static void write(Response response, Callback callback, int status, String type, String content) {
        byte[] bytes = content.getBytes(StandardCharsets.UTF_8);
        response.setStatus(status);
        response.getHeaders().put(HttpHeader.CONTENT_TYPE, type);
        response.getHeaders().put(HttpHeader.CACHE_CONTROL, "no-store");
        response.getHeaders().put(HttpHeader.CONTENT_LENGTH, bytes.length);
        response.write(true, ByteBuffer.wrap(bytes), callback);
    }

    private static void redirect(Request request, Response response, Callback callback, String location) {
        Response.sendRedirect(request, response, callback, HttpStatus.SEE_OTHER_303, location, false);
    }

    private static String value(Fields fields, String name) {
        String value = fields.getValue(name);
        return value == null ? "" : value;
    }

    private static Integer parseInt(String text) {
        try {
            return Integer.valueOf(text);
        } catch (NumberFormatException e) {
            return null;
        }
    }

    private static String escape(String text) {
        return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace("\"", "&quot;");
    }
}
