package io.dtron.selenium.sample;

import io.dtron.selenium.AbstractSeleniumAdapter;

/** An abstract adapter: scanning skips it. */
public abstract class BaseAdapter extends AbstractSeleniumAdapter {
}
