package io.dtron.selenium;

import com.sun.net.httpserver.HttpExchange;
import com.sun.net.httpserver.HttpServer;
import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.URLDecoder;
import java.nio.charset.StandardCharsets;
import java.util.List;

/** A small web site on loopback for the adapters of {@code io.dtron.selenium.sample}. */
final class TestSite implements AutoCloseable {
    private final HttpServer server;

    TestSite() throws IOException {
        server = HttpServer.create(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0), 0);
        server.createContext("/form", e -> page(e, "Form", "<form action='/hello' method='get'>"
                + "<label for='name'>Your  name</label><input id='name' name='name'>"
                + "<label>Colour <select name='colour'><option>red</option></select></label>"
                + "<input aria-label='Comment' name='comment'>"
                + "<button id='go' type='submit'>Go</button></form>"));
        server.createContext("/hello", e -> page(e, "Hello", "<h1 id='greeting'>Hello " + escape(query(e, "name"))
                + "</h1>"));
        server.createContext("/set", e -> {
            e.getResponseHeaders().add("Set-Cookie", "v=" + Integer.parseInt(query(e, "v")) + "; Path=/");
            page(e, "Stored", "<p id='stored'>stored</p>");
        });
        server.createContext("/get", e -> page(e, "Value", "<p id='value'>" + cookie(e, "v") + "</p>"));
        server.start();
    }

    /** Returns the site's address, {@code http://127.0.0.1:PORT}. */
    String url() {
        return "http://127.0.0.1:" + server.getAddress().getPort();
    }

    @Override
    public void close() {
        server.stop(0);
    }

    private static void page(HttpExchange exchange, String title, String body) throws IOException {
        byte[] bytes = ("<!DOCTYPE html><html><head><title>" + title + "</title></head><body>" + body
                + "</body></html>").getBytes(StandardCharsets.UTF_8);
        exchange.getResponseHeaders().add("Content-Type", "text/html; charset=utf-8");
        exchange.sendResponseHeaders(200, bytes.length);
        try (OutputStream out = exchange.getResponseBody()) {
            out.write(bytes);
        }
    }

    private static String query(HttpExchange exchange, String name) {
        String query = exchange.getRequestURI().getRawQuery();
        for (String pair : query == null ? new String[0] : query.split("&")) {
            int eq = pair.indexOf('=');
            if (eq > 0 && pair.substring(0, eq).equals(name)) {
                return URLDecoder.decode(pair.substring(eq + 1), StandardCharsets.UTF_8);
            }
        }
        return "";
    }

    private static String cookie(HttpExchange exchange, String name) {
        List<String> headers = exchange.getRequestHeaders().getOrDefault("Cookie", List.of());
        for (String header : headers) {
            for (String part : header.split(";")) {
                String[] kv = part.trim().split("=", 2);
                if (kv.length == 2 && kv[0].equals(name)) {
                    return kv[1];
                }
            }
        }
        return "-1";
    }

    private static String escape(String text) {
        return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;");
    }
}
