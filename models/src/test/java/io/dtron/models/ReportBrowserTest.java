package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.model.Layout;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.models.lamp.SmartLamp;
import io.dtron.models.streetlight.StreetLightModel;
import io.dtron.selenium.HeadlessChrome;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.openqa.selenium.By;
import org.openqa.selenium.OutputType;
import org.openqa.selenium.TakesScreenshot;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.WebElement;

/**
 * The report and the live view in real headless Chromium (Debian's, through chromedriver, as the Selenium adapters
 * start it): what a reader sees, asserted on the page's DOM; screenshots kept under {@code target/report-screenshots}.
 */
@Timeout(value = 180, unit = TimeUnit.SECONDS)
class ReportBrowserTest {
    static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    static final Path SCREENSHOTS = Path.of("target", "report-screenshots");

    /** Runs {@code dtron ARGS} in this JVM; its exit code and standard output and error. */
    static String[] dtron(String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = DtronCommand.run(args, new PrintWriter(out, true), new PrintWriter(err, true));
        return new String[] {Integer.toString(exit), out.toString(), err.toString()};
    }

    static Path lamp(Path dir) throws Exception {
        Files.copy(SHARED.resolve("tron/LightContr.xml"), dir.resolve("LightContr.xml"));
        Files.copy(SHARED.resolve("tron/LightContr.trn"), dir.resolve("LightContr.trn"));
        return dir.resolve("LightContr.xml");
    }

    static void awaitRendered(WebDriver browser) {
        Waits.await("the report is drawn").until(() -> "true".equals(browser.findElement(By.tagName("body"))
                .getAttribute("data-ready")));
    }

    /** A screenshot of the whole page (the window made as tall as the page, up to 6,000 pixels). */
    static void screenshot(WebDriver browser, String name) throws Exception {
        Files.createDirectories(SCREENSHOTS);
        long height = (Long) ((org.openqa.selenium.JavascriptExecutor) browser).executeScript(
                "return document.documentElement.scrollHeight");
        browser.manage().window().setSize(new org.openqa.selenium.Dimension(1280, (int) Math.min(6000, height)));
        Path shot = ((TakesScreenshot) browser).getScreenshotAs(OutputType.FILE).toPath();
        Files.copy(shot, SCREENSHOTS.resolve(name), StandardCopyOption.REPLACE_EXISTING);
    }

    /** A user who presses every 2 units or more and sees the level, for the lamps of the models below. */
    private static final String PRESSING_USER = """
            process User() { clock u; state idle; init idle;
                trans idle -> idle { guard u >= 2; sync i_press!; assign u = 0; },
                      idle -> idle { sync o_level?; }; }
            system Lamp, User;
            """;

    /**
     * Runs {@code model} (a file) against its own implementation part in virtual time with a report beside it, which
     * must pass, and opens the report in a new browser, drawn: the caller quits the browser.
     */
    static WebDriver reportOfItsOwnRun(Path model, long seed, long timeout) {
        Path page = model.resolveSibling(model.getFileName() + ".html");
        String[] run = dtron("run", model.toString(), "--sut", "model", "--virtual-time", "--seed", Long.toString(seed),
                "--timeout", Long.toString(timeout), "--report", page.toString());
        assertEquals("0", run[0], run[1] + run[2]);
        WebDriver browser = HeadlessChrome.defaults().create();
        try {
            browser.get(page.toUri().toString());
            awaitRendered(browser);
            return browser;
        } catch (RuntimeException | Error e) {
            browser.quit();
            throw e;
        }
    }

    @Test
    void theReportOfAFailedLampRunHighlightsTheFailingOutputAndMarksWhereTheRunEnded(@TempDir Path dir)
            throws Exception {
        Path model = lamp(dir);
        Path page = dir.resolve("lamp.html");
        String[] run = dtron("run", model.toString(), "--interface", dir.resolve("LightContr.trn").toString(),
                "--sut", SmartLamp.class.getName() + ":early", "--virtual-time", "--seed", "3", "--report",
                page.toString());
        assertEquals("2", run[0], run[1] + run[2]);
        Matcher state = Pattern.compile("the implementation was in (.*)\\.\\n").matcher(run[1]);
        assertTrue(state.find(), run[1]);
        Network network = ModelLoader.load(model);
        WebDriver browser = HeadlessChrome.defaults().create();
        try {
            browser.get(page.toUri().toString());
            awaitRendered(browser);
            assertEquals("FAILED", browser.findElement(By.id("verdict-word")).getText());
            assertTrue(browser.findElement(By.id("explanation")).getText().startsWith("output level(adapLevel=0)"
                    + " observed at t=198.241 is not allowed then (too early)"));
            List<WebElement> failing = browser.findElements(By.cssSelector("#events tr.failing"));
            assertEquals(1, failing.size(), "one observation is highlighted");
            String row = failing.get(0).getText();
            assertTrue(row.contains("t=198.241") && row.contains("level(adapLevel=0)") && row.contains("output"), row);
            assertTrue(failing.get(0).findElement(By.cssSelector("td.window")).getText().contains(
                    "level between t=206.241 and t=221.241"), row);
            assertEquals(1, browser.findElements(By.cssSelector("#timeline line.tick-failing")).size());
            // each process of the implementation ends where the verdict says it was; a template whose processes all
            // are of the implementation shows where they ended, and nowhere else
            java.util.Map<String, java.util.Set<String>> ends = new java.util.TreeMap<>();
            java.util.Map<String, Integer> named = new java.util.HashMap<>();
            for (String at : state.group(1).split(", ")) {
                String template = network.process(at.substring(0, at.lastIndexOf('.'))).orElseThrow().template();
                ends.computeIfAbsent(template, t -> new java.util.TreeSet<>()).add(at.substring(at.lastIndexOf('.')
                        + 1));
                named.merge(template, 1, Integer::sum);
            }
            ends.forEach((template, locations) -> {
                java.util.Set<String> ended = new java.util.TreeSet<>(browser.findElements(By.cssSelector(
                        "svg[data-template='" + template + "'] g.location.ended")).stream().map(e -> e.getAttribute(
                        "data-name")).toList());
                long processes = network.processes().stream().filter(p -> p.template().equals(template)).count();
                if (processes == named.get(template)) {
                    assertEquals(locations, ended, template);
                } else {
                    assertTrue(ended.containsAll(locations), template + ": " + ended);
                }
            });
            // the environment's user pressed (grasp!) and is busy: the edge it took is drawn as taken
            assertEquals(List.of("busy"), browser.findElements(By.cssSelector("svg[data-template='SampleUser']"
                    + " g.location.ended")).stream().map(e -> e.getAttribute("data-name")).toList());
            assertEquals(1, browser.findElements(By.cssSelector("svg[data-template='SampleUser'] g.edge.taken"))
                    .size());
            assertEquals("9/23 (39.1%)", browser.findElement(By.cssSelector("td.figure[data-figure='locations']"))
                    .getText());
            screenshot(browser, "report-failed-lamp.png");
        } finally {
            browser.quit();
        }
    }

    @Test
    void theStreetLightAndTheLampAreDrawnFromTheirSavedLayout(@TempDir Path dir) throws Exception {
        for (Path model : List.of(StreetLightModel.write(dir, 1), lamp(dir))) {
            Path page = dir.resolve(model.getFileName() + ".html");
            List<String> args = new ArrayList<>(List.of("run", model.toString(), "--sut", "model", "--virtual-time",
                    "--seed", "1", "--timeout", "200", "--report", page.toString()));
            if (model.toString().endsWith("LightContr.xml")) {
                args.addAll(List.of("--interface", dir.resolve("LightContr.trn").toString()));
            }
            String[] run = dtron(args.toArray(String[]::new));
            assertEquals("0", run[0], run[1] + run[2]);
            Network network = ModelLoader.load(model);
            Layout layout = Layout.read(model);
            WebDriver browser = HeadlessChrome.defaults().create();
            try {
                browser.get(page.toUri().toString());
                awaitRendered(browser);
                int drawn = 0;
                for (io.dtron.model.Process p : network.processes()) {
                    Layout.Template t = layout.template(p.template()).orElseThrow();
                    String svg = "svg[data-template='" + t.name() + "'] ";
                    List<WebElement> locations = browser.findElements(By.cssSelector(svg + "g.location"));
                    assertEquals(p.locations().size(), locations.size(), model + " " + t.name());
                    assertEquals(p.edges().size(), browser.findElements(By.cssSelector(svg + "g.edge")).size(),
                            model + " " + t.name());
                    for (int i = 0; i < locations.size(); i++) {
                        Layout.Point at = t.locations().get(i).at();
                        WebElement body = locations.get(i).findElement(By.cssSelector("circle.body"));
                        assertEquals(List.of(Integer.toString(at.x()), Integer.toString(at.y())),
                                List.of(body.getAttribute("cx"), body.getAttribute("cy")), t.name() + " "
                                + t.locations().get(i).name() + " where the editor saved it");
                    }
                    // a path's points: the source, the nails in order, the target (each end moved to the circle's rim)
                    for (int e = 0; e < t.edges().size(); e++) {
                        Layout.Edge edge = t.edges().get(e);
                        if (edge.nails().isEmpty()) {
                            continue;
                        }
                        String d = browser.findElement(By.cssSelector(svg + "g.edge[data-index='" + e + "'] path"))
                                .getAttribute("d");
                        for (Layout.Point nail : edge.nails()) {
                            assertTrue(d.contains(" L" + nail.x() + "," + nail.y()), d + " has nail " + nail);
                        }
                    }
                    drawn++;
                }
                assertEquals(network.processes().size(), drawn);
                assertTrue(browser.findElements(By.cssSelector("h3")).stream().noneMatch(h -> h.getText()
                        .contains("laid out automatically")), "saved positions, no automatic layout");
                screenshot(browser, model.getFileName() + ".png");
            } finally {
                browser.quit();
            }
        }
    }

    @Test
    void aModelWithoutPositionsIsLaidOutWithEveryLocationAndEdgeApart(@TempDir Path dir) throws Exception {
        Path model = Files.writeString(dir.resolve("lamp.xta"), """
                chan i_press, o_level;
                int[0,2] o_level_n;
                process Lamp() { clock x; state off, low { x <= 5 }, bright { x <= 5 }; init off;
                    trans off -> low { sync i_press?; assign x = 0; },
                          low -> bright { guard x >= 1; sync i_press?; assign x = 0; },
                          low -> off { guard x >= 5; sync o_level!; assign o_level_n = 0; },
                          bright -> off { guard x >= 5; sync o_level!; assign o_level_n = 0; },
                          bright -> bright { sync i_press?; }; }
                """ + PRESSING_USER);
        WebDriver browser = reportOfItsOwnRun(model, 2, 100);
        try {
            assertEquals(2, browser.findElements(By.xpath("//h3[contains(., 'laid out automatically')]")).size());
            List<WebElement> lamp = browser.findElements(By.cssSelector("svg[data-template='Lamp'] g.location"));
            assertEquals(List.of("off", "low", "bright"), lamp.stream().map(e -> e.getAttribute("data-name")).toList());
            assertEquals(5, browser.findElements(By.cssSelector("svg[data-template='Lamp'] g.edge")).size());
            java.util.Set<String> places = new java.util.HashSet<>();
            for (WebElement l : lamp) {
                WebElement body = l.findElement(By.cssSelector("circle.body"));
                places.add(body.getAttribute("cx") + "," + body.getAttribute("cy"));
            }
            assertEquals(3, places.size(), "no two locations on one spot: " + places);
            assertTrue(browser.findElements(By.cssSelector("svg[data-template='Lamp'] text")).stream()
                    .anyMatch(t -> t.getText().equals("x >= 1")), "the guards as written");
            // the model allows level exactly 5 units after x was reset (x >= 5 and x <= 5): each output's window is
            // the instant it came
            List<WebElement> outputs = browser.findElements(By.cssSelector("#events tr.event.output"));
            assertFalse(outputs.isEmpty(), "the lamp showed its level");
            for (WebElement row : outputs) {
                String at = row.findElements(By.cssSelector("td.num")).get(1).getText();
                assertEquals(at + " to " + at, row.findElement(By.cssSelector("td.window")).getText(), row.getText());
            }
            screenshot(browser, "report-xta.png");
        } finally {
            browser.quit();
        }
    }

    @Test
    void longLabelsAndNamesAreDrawnWholeInsideTheirTemplatesBox(@TempDir Path dir) throws Exception {
        Path model = Files.writeString(dir.resolve("long.xta"), """
                chan i_press, o_level;
                int[0,2] o_level_n;
                int[0,99] presses_counted_since_the_lamp_was_installed;
                process Lamp() { clock x; state off, on_after_a_press_that_the_lamp_has_accepted { x <= 5 }; init off;
                    trans off -> on_after_a_press_that_the_lamp_has_accepted { guard x >= 0 && presses_counted_since_the_lamp_was_installed < 99 && presses_counted_since_the_lamp_was_installed != 57; sync i_press?; assign x = 0, presses_counted_since_the_lamp_was_installed = presses_counted_since_the_lamp_was_installed + 1; },
                          on_after_a_press_that_the_lamp_has_accepted -> off { guard x >= 5; sync o_level!; assign o_level_n = 0; }; }
                """ + PRESSING_USER);
        WebDriver browser = reportOfItsOwnRun(model, 1, 50);
        try {
            Object clipped = ((org.openqa.selenium.JavascriptExecutor) browser).executeScript("""
                    var out = [];
                    document.querySelectorAll('svg[data-template] text').forEach(function (t) {
                      var v = t.ownerSVGElement.viewBox.baseVal, b = t.getBBox();
                      if (b.x < v.x || b.y < v.y || b.x + b.width > v.x + v.width || b.y + b.height > v.y + v.height) {
                        out.push(t.textContent);
                      }
                    });
                    return out.join(' | ');""");
            assertEquals("", clipped, "texts that reach out of their template's box");
            assertTrue(browser.findElements(By.cssSelector("svg[data-template='Lamp'] text")).stream()
                    .anyMatch(t -> t.getText().contains("!= 57")), "the long guard is drawn");
            screenshot(browser, "report-long-labels.png");
        } finally {
            browser.quit();
        }
    }

    @Test
    void theLiveViewUpdatesWhileTheRunGoesOnOnLoopbackOnly(@TempDir Path dir) throws Exception {
        Path model = lamp(dir);
        // the browser starts before the run, so that the run's 30 s are for watching it
        WebDriver browser = HeadlessChrome.defaults().create();
        try {
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            CompletableFuture<Integer> run = CompletableFuture.supplyAsync(() -> DtronCommand.run(new String[] {"run",
                    model.toString(), "--interface", dir.resolve("LightContr.trn").toString(), "--sut",
                    SmartLamp.class.getName(), "--seed", "4", "--timeout", "30000", "--live", "0"},
                    new PrintWriter(out, true), new PrintWriter(err, true)));
            Pattern where = Pattern.compile("dtron run: live view at (http://127\\.0\\.0\\.1:(\\d+)/)");
            Waits.await("the live view's address").until(() -> where.matcher(out.toString()).find() || run.isDone());
            Matcher m = where.matcher(out.toString());
            assertTrue(m.find(), out + "\n" + err);
            assertEquals(List.of("127.0.0.1"), listeners(Integer.parseInt(m.group(2))), "loopback only, as ss shows");
            browser.get(m.group(1));
            WebElement body = browser.findElement(By.tagName("body"));
            Waits.await("the page shows events of the run").until(() -> events(body) > 0);
            int first = events(body);
            boolean running = !run.isDone() && body.getAttribute("data-verdict").isEmpty();
            Waits.await("the page shows more events").until(() -> events(body) > first || run.isDone());
            assertTrue(running && events(body) > first, "the page updated while the run went on: " + out);
            int exit = run.get(120, TimeUnit.SECONDS);
            String verdict = exit == 0 ? "PASSED" : exit == 2 ? "FAILED" : "INCONCLUSIVE";
            Waits.await("the page shows the verdict").until(() -> verdict.equals(body.getAttribute("data-verdict")));
            Matcher stats = Pattern.compile("statistics: \\d+ \\w+ (\\d+) (\\d+) ").matcher(out.toString());
            assertTrue(stats.find(), out.toString());
            assertEquals(Integer.parseInt(stats.group(1)) + Integer.parseInt(stats.group(2)), events(body),
                    "every input and output of the run is on the page");
            screenshot(browser, "live-lamp.png");
        } finally {
            browser.quit();
        }
    }

    private static int events(WebElement body) {
        String n = body.getAttribute("data-events");
        return n == null || n.isEmpty() ? -1 : Integer.parseInt(n);
    }

    /** The addresses {@code ss -ltn} lists a listener on {@code port} at, as ss writes them. */
    private static List<String> listeners(int port) throws Exception {
        Process ss = new ProcessBuilder("ss", "-ltn").redirectErrorStream(true).start();
        String listing = new String(ss.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        assertEquals(0, ss.waitFor(), listing);
        List<String> addresses = new ArrayList<>();
        for (String line : listing.lines().toList()) {
            String[] f = line.trim().split("\\s+");
            if (f.length > 3 && f[3].endsWith(":" + port)) {
                String a = f[3].substring(0, f[3].length() - (":" + port).length());
                addresses.add(a.equals("[::ffff:127.0.0.1]") ? "127.0.0.1" : a);
            }
        }
        assertFalse(addresses.isEmpty(), listing);
        return addresses;
    }
}
