package io.dtron.selenium;

import io.dtron.selenium.internal.Messages;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Objects;
import java.util.logging.Level;
import java.util.stream.Stream;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.WebDriverException;
import org.openqa.selenium.chrome.ChromeDriver;
import org.openqa.selenium.chrome.ChromeDriverService;
import org.openqa.selenium.chrome.ChromeOptions;
import org.openqa.selenium.remote.http.ClientConfig;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Starts headless Chromium through chromedriver, one browser with a fresh profile folder per call, with the
 * flags a locked-down machine needs (no sandbox, no GPU, no connections of Chromium's own to the outside), and
 * with timeouts that make a wrong locator or a page that does not load fail fast instead of hanging, and a bound on
 * every WebDriver call ({@link #commandTimeout()}), so that a browser that stops answering cannot hold a step. Quitting
 * the browser stops its chromedriver and deletes its profile. Thread-safe.
 */
public final class HeadlessChrome implements WebDriverFactory {
    /** The flags every browser gets, besides its {@code --user-data-dir}. */
    public static final List<String> ARGUMENTS = List.of("--headless", "--no-sandbox", "--disable-gpu",
            "--disable-quic", "--no-first-run", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", "--disable-dev-shm-usage", "--window-size=1280,900");

    private static final Logger LOG = LoggerFactory.getLogger(HeadlessChrome.class);
    private static final Duration COMMAND_MARGIN = Duration.ofSeconds(15);
    /**
     * Selenium warns through java.util.logging, at every start, that it has no DevTools support for a Chromium
     * newer than itself; the adapters do not use DevTools. Kept in a field: java.util.logging holds loggers
     * weakly, and a collected logger would forget its level.
     */
    private static final java.util.logging.Logger CDP_VERSION_LOGGER =
            java.util.logging.Logger.getLogger("org.openqa.selenium.devtools.CdpVersionFinder");

    static {
        CDP_VERSION_LOGGER.setLevel(Level.SEVERE);
    }

    private final Path chromium;
    private final Path chromedriver;
    private final Duration implicitWait;
    private final Duration pageLoadTimeout;
    private final List<String> extraArguments;

    private HeadlessChrome(Builder builder) {
        this.chromium = builder.chromium;
        this.chromedriver = builder.chromedriver;
        this.implicitWait = builder.implicitWait;
        this.pageLoadTimeout = builder.pageLoadTimeout;
        this.extraArguments = List.copyOf(builder.extraArguments);
    }

    /** Returns a factory with the defaults: Debian's paths, implicit wait 2 s, page-load timeout 15 s. */
    public static HeadlessChrome defaults() {
        return builder().build();
    }

    /** Returns a builder with the defaults. */
    public static Builder builder() {
        return new Builder();
    }

    /** Returns how long a search for an element waits for it to appear. */
    public Duration implicitWait() {
        return implicitWait;
    }

    @Override
    public WebDriver create() {
        requireExecutable(chromium, "Chromium");
        requireExecutable(chromedriver, "chromedriver");
        Path profile;
        try {
            profile = Files.createTempDirectory("dtron-chromium-");
        } catch (IOException e) {
            throw new AdapterException("cannot create a profile folder for Chromium: " + e.getMessage(), e);
        }
        ChromeOptions options = new ChromeOptions();
        options.setBinary(chromium.toFile());
        List<String> arguments = new ArrayList<>(ARGUMENTS);
        arguments.addAll(extraArguments);
        arguments.add("--user-data-dir=" + profile);
        options.addArguments(arguments);
        ChromeDriverService service = new ChromeDriverService.Builder()
                .usingDriverExecutable(chromedriver.toFile())
                .usingAnyFreePort()
                .build();
        long start = System.nanoTime();
        ChromeDriver driver;
        try {
            driver = new ProfileChromeDriver(service, options, clientConfig(), profile);
        } catch (WebDriverException e) {
            service.stop();
            deleteProfile(profile);
            throw new AdapterException("cannot start " + chromium + " through " + chromedriver + ": "
                    + Messages.firstLine(e.getMessage()), e);
        }
        try {
            driver.manage().timeouts().implicitlyWait(implicitWait);
            driver.manage().timeouts().pageLoadTimeout(pageLoadTimeout);
        } catch (WebDriverException e) {
            driver.quit();
            throw new AdapterException("cannot set the timeouts of Chromium: " + Messages.firstLine(e.getMessage()), e);
        }
        LOG.debug("Started headless Chromium in {} ms with profile {}", (System.nanoTime() - start) / 1_000_000,
                profile);
        return driver;
    }

    /**
     * Returns how long a WebDriver call may wait for chromedriver's answer: the page-load timeout and 15 s more, so
     * that a chromedriver or browser that does not answer fails the call (a {@code TimeoutException}) instead of
     * holding the user's step for Selenium's default of three minutes.
     */
    public Duration commandTimeout() {
        return pageLoadTimeout.plus(COMMAND_MARGIN);
    }

    private ClientConfig clientConfig() {
        return ClientConfig.defaultConfig().readTimeout(commandTimeout());
    }

    @Override
    public String toString() {
        return "HeadlessChrome[" + chromium + ", " + chromedriver + ", implicit wait " + implicitWait.toMillis()
                + " ms, page load " + pageLoadTimeout.toMillis() + " ms]";
    }

    private static void requireExecutable(Path file, String what) {
        if (!Files.isExecutable(file)) {
            throw new AdapterException("no " + what + " at " + file + ": install Debian's chromium and"
                    + " chromium-driver (apt-get install chromium chromium-driver), or give its path");
        }
    }

    private static void deleteProfile(Path profile) {
        // Chromium may still be writing for a moment after it quit: try a few times
        for (int attempt = 0; attempt < 5; attempt++) {
            try (Stream<Path> files = Files.walk(profile)) {
                for (Path p : files.sorted(Comparator.reverseOrder()).toList()) {
                    Files.deleteIfExists(p);
                }
                return;
            } catch (IOException e) {
                try {
                    Thread.sleep(100);
                } catch (InterruptedException interrupted) {
                    Thread.currentThread().interrupt();
                    break;
                }
            }
        }
        LOG.warn("Could not delete the Chromium profile {}", profile);
    }

    /** A ChromeDriver whose quit also deletes its profile folder. */
    private static final class ProfileChromeDriver extends ChromeDriver {
        private final Path profile;

        ProfileChromeDriver(ChromeDriverService service, ChromeOptions options, ClientConfig config, Path profile) {
            super(service, options, config);
            this.profile = profile;
        }

        @Override
        public void quit() {
            try {
                super.quit();
            } finally {
                deleteProfile(profile);
            }
        }
    }

    /** Builds a {@link HeadlessChrome}. Not thread-safe. */
    public static final class Builder {
        private Path chromium = Path.of("/usr/bin/chromium");
        private Path chromedriver = Path.of("/usr/bin/chromedriver");
        private Duration implicitWait = Duration.ofSeconds(2);
        private Duration pageLoadTimeout = Duration.ofSeconds(15);
        private final List<String> extraArguments = new ArrayList<>();

        private Builder() {
        }

        /** Sets the Chromium executable (default {@code /usr/bin/chromium}). */
        public Builder chromium(Path executable) {
            chromium = Objects.requireNonNull(executable, "executable");
            return this;
        }

        /** Sets the chromedriver executable (default {@code /usr/bin/chromedriver}). */
        public Builder chromedriver(Path executable) {
            chromedriver = Objects.requireNonNull(executable, "executable");
            return this;
        }

        /** Sets how long a search for an element waits for it to appear (default 2 s). */
        public Builder implicitWait(Duration wait) {
            implicitWait = requirePositive(wait, "implicit wait");
            return this;
        }

        /** Sets how long a page may take to load (default 15 s). */
        public Builder pageLoadTimeout(Duration timeout) {
            pageLoadTimeout = requirePositive(timeout, "page-load timeout");
            return this;
        }

        /** Adds a Chromium flag to {@link #ARGUMENTS}. */
        public Builder argument(String flag) {
            extraArguments.add(Objects.requireNonNull(flag, "flag"));
            return this;
        }

        /** Builds the factory. */
        public HeadlessChrome build() {
            return new HeadlessChrome(this);
        }

        private static Duration requirePositive(Duration d, String what) {
            if (Objects.requireNonNull(d, what).isNegative() || d.isZero()) {
                throw new IllegalArgumentException(what + " must be positive: " + d);
            }
            return d;
        }
    }
}
